#include "atomic_output.hpp"

#include "terratin/error.hpp"

#include <dirent.h>
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
#include <vector>

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
                           bool overwrite) {
    refuseIrregularOutputs(stage, candidates);
    const auto existing = existingFiles(candidates);
    if (!existing.empty() && !overwrite)
        throw InvalidInputError(std::string(stage) + ": the output " + quoted(existing.front()) +
                                " exists; use " + markOption("overwrite"));
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

/// The levels a temporary has: a file (1), or a directory of files (2: a Shapefile's
/// components); its removal goes no deeper.
constexpr int kTemporaryDepth = 2;

/// Whether the directory open as `fd` is the one `path` names now (same device and inode).
bool sameDirectory(int fd, const fs::path& path) {
    struct stat held {};
    struct stat named {};
    return ::fstat(fd, &held) == 0 && ::stat(path.c_str(), &named) == 0 &&
           held.st_dev == named.st_dev && held.st_ino == named.st_ino;
}

/// The names in the directory open as `directory` ("." and ".." left out); empty when it
/// cannot be read.
std::vector<std::string> entryNames(int directory) {
    std::vector<std::string> names;
    // A descriptor of its own: fdopendir takes it over, and reads from its own position.
    const int listing = ::openat(directory, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (listing < 0)
        return names;
    DIR* const stream = ::fdopendir(listing);
    if (stream == nullptr) {
        ::close(listing);
        return names;
    }
    while (const dirent* entry = ::readdir(stream)) {
        const std::string name = entry->d_name;
        if (name != "." && name != "..")
            names.push_back(name);
    }
    ::closedir(stream);
    return names;
}

/// Removes `name` in `directory`, and for a directory what it holds, `depth` levels down.
void removeTree(int directory, const std::string& name, int depth) {
    if (::unlinkat(directory, name.c_str(), 0) == 0 || errno == ENOENT)
        return;
    if ((errno != EISDIR && errno != EPERM) || depth <= 1)
        return;
    const int inner =
        ::openat(directory, name.c_str(), O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (inner < 0)
        return;
    for (const std::string& entry : entryNames(inner))
        removeTree(inner, entry, depth - 1);
    ::close(inner);
    ::unlinkat(directory, name.c_str(), AT_REMOVEDIR);
}

/// Removes every entry of `directory` whose name starts with `prefix`.
void removeStartingWith(int directory, const std::string& prefix) {
    for (const std::string& name : entryNames(directory))
        if (name.starts_with(prefix))
            removeTree(directory, name, kTemporaryDepth);
}

/// Moves `from` to `to` (each a directory descriptor and a name in it) unless `to` exists, as
/// one atomic step. Returns 0 or an errno value (EEXIST when `to` exists).
int renameNoReplace(int fromDirectory, const char* from, int toDirectory, const char* to) {
    if (::renameat2(fromDirectory, from, toDirectory, to, RENAME_NOREPLACE) == 0)
        return 0;
    if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP)
        return errno;
    // No RENAME_NOREPLACE on this file system (some NFS and FUSE ones): link(2) refuses an
    // existing name just as atomically; the temporary name is removed afterwards.
    if (::linkat(fromDirectory, from, toDirectory, to, 0) == 0) {
        ::unlinkat(fromDirectory, from, 0);
        return 0;
    }
    if (errno != EPERM && errno != EOPNOTSUPP && errno != EMLINK)
        return errno;
    // No hard links either (FAT, some FUSE): check, then rename. Another program can still
    // slip in between the two; no atomic way is left on such a file system.
    struct stat status {};
    if (::fstatat(toDirectory, to, &status, AT_SYMLINK_NOFOLLOW) == 0)
        return EEXIST;
    return ::renameat(fromDirectory, from, toDirectory, to) == 0 ? 0 : errno;
}

} // namespace

AtomicOutput::AtomicOutput(std::string_view stage, const fs::path& output, ExistingTarget existing)
    : m_stage(stage), m_directory(outputDirectory(output)), m_existing(existing),
      m_overwriteName(markOption("overwrite")) {
    std::random_device device;
    const std::uint64_t random =
        (static_cast<std::uint64_t>(device()) << 32U) ^ static_cast<std::uint64_t>(device());
    std::ostringstream unique;
    unique << ".tmp-" << ::getpid() << '-' << std::hex << random;
    // The longest temporary is the prefix plus the output's extension (temporary()'s contract),
    // and side files add to it: a legal output name of up to 255 bytes must still give legal
    // temporary names, so the stem gives way.
    const std::size_t fixed =
        1 + unique.str().size() + output.extension().string().size() + kSideFileBytes;
    const std::size_t stemBytes = fixed < kMaxNameBytes ? kMaxNameBytes - fixed : 0;
    std::ostringstream prefix;
    prefix << '.' << utf8Prefix(output.stem().string(), stemBytes) << unique.str();
    m_prefix = prefix.str();
    // O_PATH: only search permission is needed, and the *at calls take it as their directory.
    const int directory = ::open(m_directory.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (directory >= 0)
        m_directoryFd = directory;
}

AtomicOutput::~AtomicOutput() {
    removeAll();
    if (m_directoryFd)
        ::close(*m_directoryFd);
}

AtomicOutput::Location AtomicOutput::locate(const fs::path& path) const {
    if (m_directoryFd) {
        const fs::path inside = path.lexically_relative(m_directory);
        if (!inside.empty() && *inside.begin() != ".." && *inside.begin() != ".")
            return {*m_directoryFd, inside.string()};
    }
    return {AT_FDCWD, path.string()};
}

void AtomicOutput::refuseMovedDirectory(const fs::path& target) const {
    // Checked before the rename, so a move between the two still lands the output in the moved
    // directory: nothing closes that gap, as a directory cannot be locked against a rename.
    if (!m_directoryFd || sameDirectory(*m_directoryFd, m_directory))
        return;
    throw IoError(m_stage + ": the output directory " + quoted(m_directory) +
                  " was moved or replaced while this run was writing; " + quoted(target) +
                  " was not written");
}

fs::path AtomicOutput::temporary(std::string_view suffix) const {
    return m_directory / (m_prefix + std::string(suffix));
}

void AtomicOutput::commit(const fs::path& temporary, const fs::path& target) const {
    refuseMovedDirectory(target);
    const Location from = locate(temporary);
    const Location to = locate(target);
    if (m_existing == ExistingTarget::Replace) {
        if (::renameat(from.directory, from.name.c_str(), to.directory, to.name.c_str()) == 0)
            return;
        const int error = errno;
        throw IoError(m_stage + ": cannot move the finished file to " + quoted(target) + ": " +
                      std::strerror(error));
    }
    const int error =
        renameNoReplace(from.directory, from.name.c_str(), to.directory, to.name.c_str());
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
                const Location put = locate(moves[i].second);
                removeTree(put.directory, put.name, 1);
            }
        throw;
    }
}

// Never throws: it runs while an exception may already be propagating.
void AtomicOutput::removeAll() noexcept {
    try {
        if (m_directoryFd)
            removeStartingWith(*m_directoryFd, m_prefix);
        // What GDAL or SQLite created by path after the directory moved (a journal) went to
        // whatever has that path now. The prefix holds this process's id and 64 random bits:
        // only this run's files start with it.
        if (!m_directoryFd || !sameDirectory(*m_directoryFd, m_directory)) {
            const int named = ::open(m_directory.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
            if (named >= 0) {
                removeStartingWith(named, m_prefix);
                ::close(named);
            }
        }
    } catch (...) {
        // Out of memory while listing: nothing sensible left to do in a destructor.
    }
}

} // namespace terratin::io::detail
