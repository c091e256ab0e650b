#include "atomic_output.hpp"

#include "terratin/error.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdint>
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
    if (!fs::exists(status))
        throw IoError(prefix + "the output directory " + quoted(directory) + " does not exist");
    if (!fs::is_directory(status))
        throw IoError(prefix + "the output's parent " + quoted(directory) +
                      " is not a directory");
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

void refuseExistingOutputs(std::string_view stage, const std::vector<fs::path>& candidates,
                           bool overwrite) {
    const auto existing = existingFiles(candidates);
    if (!existing.empty() && !overwrite)
        throw InvalidInputError(std::string(stage) + ": the output " + quoted(existing.front()) +
                                " exists; use --overwrite");
    for (const auto& file : existing) {
        std::error_code error;
        if (fs::is_directory(file, error))
            throw IoError(std::string(stage) + ": the output " + quoted(file) +
                          " is a directory, not a file");
    }
}

AtomicOutput::AtomicOutput(std::string_view stage, const fs::path& output)
    : m_stage(stage), m_directory(outputDirectory(output)) {
    std::random_device device;
    const std::uint64_t random =
        (static_cast<std::uint64_t>(device()) << 32U) ^ static_cast<std::uint64_t>(device());
    std::ostringstream prefix;
    prefix << '.' << output.stem().string() << ".tmp-" << ::getpid() << '-' << std::hex << random;
    m_prefix = prefix.str();
}

AtomicOutput::~AtomicOutput() { removeAll(); }

fs::path AtomicOutput::temporary(std::string_view suffix) const {
    return m_directory / (m_prefix + std::string(suffix));
}

void AtomicOutput::commit(const fs::path& temporary, const fs::path& target) const {
    std::error_code error;
    fs::rename(temporary, target, error);
    if (error)
        throw IoError(m_stage + ": cannot move the finished file to " + quoted(target) + ": " +
                      error.message());
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
