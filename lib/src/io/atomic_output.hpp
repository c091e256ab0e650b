#pragma once
/// @file
/// AtomicOutput: every file of one write goes under a temporary name in the output's own
/// directory (same file system, so the final rename(2) is atomic and never copies), and is
/// renamed into place only when complete. Whatever happens, every directory entry that starts
/// with the run's temporary prefix is removed when the AtomicOutput goes out of scope: SQLite
/// journals, GDAL side files ("<temporary>.gpkg.tmp_rtree_<layer>.db", FlatGeobuf's feature
/// buffer) and the temporaries themselves.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace terratin::io::detail {

/// '<path>' for messages.
std::string quoted(const std::filesystem::path& path);

/// The directory an output goes into ("." for a bare file name).
std::filesystem::path outputDirectory(const std::filesystem::path& output);

/// Refuses, with errors that start with `stage`, an output that names no file or a directory
/// (IoError), or whose directory is missing, not a directory or not writable (IoError).
void checkOutputLocation(std::string_view stage, const std::filesystem::path& output);

/// The entries of `candidates` that exist (as anything, dangling links included).
std::vector<std::filesystem::path> existingFiles(const std::vector<std::filesystem::path>& candidates);

/// InvalidInputError "<stage>: the output '<first>' exists; use --overwrite" when any of
/// `candidates` exists and `overwrite` is false; IoError when one of them is a directory.
void refuseExistingOutputs(std::string_view stage,
                           const std::vector<std::filesystem::path>& candidates, bool overwrite);

/// One write's temporary names, removed on destruction.
class AtomicOutput {
public:
    /// Prefix ".<stem>.tmp-<pid>-<64 random bits>" in the directory of `output`.
    AtomicOutput(std::string_view stage, const std::filesystem::path& output);
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;
    ~AtomicOutput();

    /// directory / (prefix + suffix): a name no other run uses.
    [[nodiscard]] std::filesystem::path temporary(std::string_view suffix) const;

    /// Renames `temporary` onto `target`, replacing it atomically; IoError on failure.
    void commit(const std::filesystem::path& temporary, const std::filesystem::path& target) const;

private:
    void removeAll() noexcept;

    std::string m_stage;
    std::filesystem::path m_directory;
    std::string m_prefix;
};

} // namespace terratin::io::detail
