#pragma once
/// @file
/// --qgis-style's terrain style (.qml) beside a vector output, written as one with the data:
/// to a temporary before the data is put in place, renamed after it, and the data this run
/// created taken back when the style cannot follow (another program created one there
/// meanwhile, and there is no overwrite). Used by writeTin and by the TIN written tile by tile
/// (tin_stream.hpp).

#include "atomic_output.hpp"
#include "terratin/io/tin_writer.hpp"

#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

namespace terratin::io::detail {

/// The style of `output`: its path with the extension .qml (QGIS's default style file).
std::filesystem::path stylePath(const std::filesystem::path& output);

class StyleBeside {
public:
    /// Before the data's first byte: notes which of `dataFiles` do not exist yet, the ones this
    /// run creates.
    StyleBeside(std::string_view stage, const std::filesystem::path& output,
                const std::vector<std::filesystem::path>& dataFiles,
                const TinWriteOptions& options);

    /// The style colouring z_mean from `lowest` to `highest`, to its temporary. Throws IoError.
    void write(double lowest, double highest);
    /// After the data is in place: the style too. When it cannot be, the data files this run
    /// created are removed again and the error is rethrown.
    void commit() const;

private:
    std::filesystem::path m_style;
    AtomicOutput m_temporaries;
    std::filesystem::path m_temporary;
    std::vector<std::filesystem::path> m_created;
    std::string m_stage;
};

} // namespace terratin::io::detail
