#pragma once
/// @file
/// AtomicOutput: every file of one write goes under a temporary name in the output's own
/// directory (same file system, so the final rename(2) is atomic and never copies), and is
/// renamed into place only when complete. Whatever happens, every directory entry that starts
/// with the run's temporary prefix is removed when the AtomicOutput goes out of scope: SQLite
/// journals, GDAL side files ("<temporary>.gpkg.tmp_rtree_<layer>.db", FlatGeobuf's feature
/// buffer) and the temporaries themselves.
///
/// An output that is not to be replaced is checked before the first byte is written
/// (refuseExistingOutputs), and again, atomically, by the final rename: one that another
/// program created while the run was writing is left as it is.
///
/// The output's directory is held open from the start, and the final rename and the removal go
/// through it (renameat, unlinkat): a directory renamed while the run writes (by a user, a sync
/// tool) keeps nothing of the run, wherever it went, and the final rename refuses it rather
/// than put the output where it was not asked for.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
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
std::vector<std::filesystem::path>
existingFiles(const std::vector<std::filesystem::path>& candidates);

/// IoError when one of `candidates` exists and is not a regular file: a directory, a symbolic
/// link (even to a regular file: replacing it would cut the link, not write its target), a
/// character or block device (/dev/null), a FIFO or a socket.
void refuseIrregularOutputs(std::string_view stage,
                            const std::vector<std::filesystem::path>& candidates);

/// refuseIrregularOutputs, then InvalidInputError "<stage>: the output '<first>' exists; use
/// overwrite" (the option marked, markOption) when any of `candidates` exists and
/// `overwrite` is false.
void refuseExistingOutputs(std::string_view stage,
                           const std::vector<std::filesystem::path>& candidates, bool overwrite);

/// What the final rename does with a target that exists by then.
enum class ExistingTarget {
    /// Leave it as it is and throw InvalidInputError: without overwrite, a target that exists
    /// at the end was created by someone else while the run was writing.
    Refuse,
    /// Replace it atomically (overwrite, or a GeoPackage copied to add layers to it).
    Replace,
};

/// Replace with `overwrite`, Refuse without.
inline ExistingTarget existingTargetFor(bool overwrite) {
    return overwrite ? ExistingTarget::Replace : ExistingTarget::Refuse;
}

/// One write's temporary names, removed on destruction.
class AtomicOutput {
public:
    /// Prefix ".<stem>.tmp-<pid>-<64 random bits>" in the directory of `output`; the stem is
    /// cut short when the temporary names would pass the file system's 255-byte name limit.
    /// A refused target's message points to the overwrite option (marked, markOption).
    AtomicOutput(std::string_view stage, const std::filesystem::path& output,
                 ExistingTarget existing);
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;
    ~AtomicOutput();

    /// directory / (prefix + suffix): a name no other run uses. `suffix` is at most as long as
    /// the output's extension (".gpkg", "" for a directory), or the name may be too long.
    [[nodiscard]] std::filesystem::path temporary(std::string_view suffix) const;

    /// Renames `temporary` onto `target` as one atomic step. With ExistingTarget::Refuse an
    /// existing `target` is left untouched and InvalidInputError is thrown; IoError when the
    /// output directory is no longer where it was (moved or replaced since construction) and
    /// on any other failure.
    void commit(const std::filesystem::path& temporary, const std::filesystem::path& target) const;

    /// commit() for each (temporary, target) in order. With ExistingTarget::Refuse, a failure
    /// removes again the targets this call had already put in place (they did not exist before
    /// it), so that a refused Shapefile leaves no component of its own behind.
    void commitAll(
        const std::vector<std::pair<std::filesystem::path, std::filesystem::path>>& moves) const;

private:
    /// Where `path` is for the *at calls: its name in the held directory, or the path itself
    /// (relative to the working directory) when it is not in it or the directory is not held.
    struct Location {
        int directory;
        std::string name;
    };
    [[nodiscard]] Location locate(const std::filesystem::path& path) const;
    /// IoError naming `target` when m_directory no longer names the held directory.
    void refuseMovedDirectory(const std::filesystem::path& target) const;
    void removeAll() noexcept;

    std::string m_stage;
    std::filesystem::path m_directory;
    /// m_directory, opened at construction; nullopt when it could not be opened (no file
    /// descriptor left, or the directory gone already): then every step goes by path.
    std::optional<int> m_directoryFd;
    std::string m_prefix;
    ExistingTarget m_existing;
    /// "overwrite" or "--overwrite", for the message of a refused target.
    std::string m_overwriteName;
};

} // namespace terratin::io::detail
