#include "atomic_output.hpp"

#include "terratin/error.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <sstream>
#include <system_error>

namespace terratin::io::detail {

namespace fs = std::filesystem;

std::string quoted(const fs::path& path) {
    // Appended piecewise: GCC 12 reports a spurious -Wrestrict for "'" + string + "'".
    std::string text = "'";
    text += path.string();
    text += '\'';
    return text;
}

fs::path outputDirectory(const fs::path& output) {
    return output.has_parent_path() ? output.parent_path() : fs::path(".");
}

void checkOutputLocation(std::string_view stage, const fs::path& output) {
    const std::string prefix = std::string(stage) + ": ";
    std::error_code error;
    if (output.filename().empty() || output.filename() == "." || output.filename() == "..")
        throw InvalidInputError(prefix + "the output " + quoted(output) + " names no file");
    if (fs::is_directory(output, error))
        throw IoError(prefix + "the output " + quoted(output) + " is a directory, not a file");

    const fs::path directory = outputDirectory(output);
    const auto status = fs::status(directory, error);
    // Say what is wrong with a directory that cannot be looked at (a symbolic link loop, no
    // permission) instead of calling it missing.
    if (!fs::exists(status) && error && error != std::errc::no_such_file_or_directory)
        throw IoError(prefix + "the output directory " + quoted(directory) +
                      " cannot be looked at: " + error.message());
    if (!fs::exists(status))
        throw IoError(prefix + "the output directory " + quoted(directory) + " does not exist");
    if (!fs::is_directory(status))
        throw IoError(prefix + "the output's parent " + quoted(directory) + " is not a directory");
    // Write and search permission are both needed to create and rename entries.
    if (::access(directory.c_str(), W_OK | X_OK) != 0)
        throw IoError(prefix + "the output directory " + quoted(directory) +
                      " is not writable: " + std::strerror(errno));
}

std::vector<fs::path> existingFiles(const std::vector<fs::path>& candidates) {
    std::vector<fs::path> existing;
    for (const auto& candidate : candidates) {
        std::error_code error;
        if (fs::exists(fs::symlink_status(candidate, error)))
            existing.push_back(candidate);
    }
    return existing;
}

namespace {

/// What a non-regular file is, for "the output 'x' is <kind>", or empty for a regular file.
std::string irregularKind(fs::file_type type) {
    switch (type) {
    case fs::file_type::regular:
        return {};
    case fs::file_type::directory:
        return "a directory, not a file";
    case fs::file_type::symlink:
        return "a symbolic link; only regular files are replaced (write to its target instead)";
    case fs::file_type::character:
        return "a character device, not a regular file; it is never replaced";
    case fs::file_type::block:
        return "a block device, not a regular file; it is never replaced";
    case fs::file_type::fifo:
        return "a FIFO (named pipe), not a regular file; it is never replaced";
    case fs::file_type::socket:
        return "a socket, not a regular file; it is never replaced";
    default:
        return "not a regular file; it is never replaced";
    }
}

} // namespace

void refuseIrregularOutputs(std::string_view stage, const std::vector<fs::path>& candidates) {
    for (const auto& file : existingFiles(candidates)) {
        std::error_code error;
        const std::string kind = irregularKind(fs::symlink_status(file, error).type());
        if (!kind.empty())
            throw IoError(std::string(stage) + ": the output " + quoted(file) + " is " + kind);
    }
}

void refuseExistingOutputs(std::string_view stage, const std::vector<fs::path>& candidates,
                           bool overwrite, const OptionNamer& optionName) {
    refuseIrregularOutputs(stage, candidates);
    const auto existing = existingFiles(candidates);
    if (!existing.empty() && !overwrite)
        throw InvalidInputError(std::string(stage) + ": the output " + quoted(existing.front()) +
                                " exists; use " + optionName("overwrite"));
}

namespace {

/// NAME_MAX of every Linux file system terratin writes to: the longest directory entry, in
/// bytes.
constexpr std::size_t kMaxNameBytes = 255;
/// Bytes kept free after a temporary's own name for the side files others name after it:
/// SQLite's "-journal" (8), GDAL's "_temp.fgb"-style buffers. Generous on purpose: a few
/// characters of the stem are all it costs.
constexpr std::size_t kSideFileBytes = 32;

/// `text` cut to at most `bytes`, never inside a UTF-8 sequence.
std::string utf8Prefix(const std::string& text, std::size_t bytes) {
    if (text.size() <= bytes)
        return text;
    std::size_t cut = bytes;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U)
        --cut;
    return text.substr(0, cut);
}

/// Moves `from` to `to` unless `to` exists, as one atomic step. Returns 0 or an errno value
/// (EEXIST when `to` exists).
int renameNoReplace(const fs::path& from, const fs::path& to) {
    if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0)
        return 0;
    if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP)
        return errno;
    // No RENAME_NOREPLACE on this file system (some NFS and FUSE ones): link(2) refuses an
    // existing name just as atomically; the temporary name is removed afterwards.
    if (::link(from.c_str(), to.c_str()) == 0) {
        ::unlink(from.c_str());
        return 0;
    }
    if (errno != EPERM && errno != EOPNOTSUPP && errno != EMLINK)
        return errno;
    // No hard links either (FAT, some FUSE): check, then rename. Another program can still
    // slip in between the two; no atomic way is left on such a file system.
    struct stat status {};
    if (::lstat(to.c_str(), &status) == 0)
        return EEXIST;
    return ::rename(from.c_str(), to.c_str()) == 0 ? 0 : errno;
}

} // namespace

AtomicOutput::AtomicOutput(std::string_view stage, const fs::path& output, ExistingTarget existing,
                           const OptionNamer& optionName)
    : m_stage(stage), m_directory(outputDirectory(output)), m_existing(existing),
      m_overwriteName(optionName("overwrite")) {
    std::random_device device;
    const std::uint64_t random =
        (static_cast<std::uint64_t>(device()) << 32U) ^ static_cast<std::uint64_t>(device());
    std::ostringstream unique;
    unique << ".tmp-" << ::getpid() << '-' << std::hex << random;
    // The longest temporary is the prefix plus the output's extension (temporary()'s contract),
    // and side files add to it: a legal output name of up to 255 bytes must still give legal
    // temporary names (issue 22, D17), so the stem gives way.
    const std::size_t fixed =
        1 + unique.str().size() + output.extension().string().size() + kSideFileBytes;
    const std::size_t stemBytes = fixed < kMaxNameBytes ? kMaxNameBytes - fixed : 0;
    std::ostringstream prefix;
    prefix << '.' << utf8Prefix(output.stem().string(), stemBytes) << unique.str();
    m_prefix = prefix.str();
}

AtomicOutput::~AtomicOutput() {
    removeAll();
}

fs::path AtomicOutput::temporary(std::string_view suffix) const {
    return m_directory / (m_prefix + std::string(suffix));
}

void AtomicOutput::commit(const fs::path& temporary, const fs::path& target) const {
    if (m_existing == ExistingTarget::Replace) {
        std::error_code error;
        fs::rename(temporary, target, error);
        if (error)
            throw IoError(m_stage + ": cannot move the finished file to " + quoted(target) + ": " +
                          error.message());
        return;
    }
    const int error = renameNoReplace(temporary, target);
    if (error == EEXIST || error == ENOTEMPTY)
        throw InvalidInputError(m_stage + ": the output " + quoted(target) +
                                " appeared while this run was writing; it was left as it is "
                                "(use " +
                                m_overwriteName + " to replace it)");
    if (error != 0)
        throw IoError(m_stage + ": cannot move the finished file to " + quoted(target) + ": " +
                      std::strerror(error));
}

void AtomicOutput::commitAll(const std::vector<std::pair<fs::path, fs::path>>& moves) const {
    std::size_t done = 0;
    try {
        for (; done < moves.size(); ++done)
            commit(moves[done].first, moves[done].second);
    } catch (...) {
        // Refuse: the targets put in place so far did not exist before, so they are this run's
        // own and go again. Replace: the old files are gone already; nothing to restore.
        if (m_existing == ExistingTarget::Refuse)
            for (std::size_t i = 0; i < done; ++i) {
                std::error_code ignored;
                fs::remove(moves[i].second, ignored);
            }
        throw;
    }
}

// Never throws: it runs while an exception may already be propagating.
void AtomicOutput::removeAll() noexcept {
    try {
        std::error_code error;
        std::vector<fs::path> doomed;
        for (fs::directory_iterator it(m_directory, error), end; !error && it != end;
             it.increment(error)) {
            if (it->path().filename().string().starts_with(m_prefix))
                doomed.push_back(it->path());
        }
        for (const auto& entry : doomed)
            fs::remove_all(entry, error);
    } catch (...) {
        // Out of memory while listing: nothing sensible left to do in a destructor.
    }
}

} // namespace terratin::io::detail
