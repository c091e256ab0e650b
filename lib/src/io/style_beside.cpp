#include "style_beside.hpp"

#include "buffered_file.hpp"
#include "qgis_style.hpp"
#include "terratin/error.hpp"

#include <system_error>

namespace terratin::io::detail {

namespace fs = std::filesystem;

fs::path stylePath(const fs::path& output) {
    fs::path style = output;
    style.replace_extension(".qml");
    return style;
}

StyleBeside::StyleBeside(std::string_view stage, const fs::path& output,
                         const std::vector<fs::path>& dataFiles, const TinWriteOptions& options)
    : m_style(stylePath(output)),
      m_temporaries(stage, m_style, existingTargetFor(options.overwrite)),
      m_temporary(m_temporaries.temporary(".qml")), m_stage(stage) {
    for (const auto& file : dataFiles)
        if (existingFiles({file}).empty() && file != m_style)
            m_created.push_back(file);
}

void StyleBeside::write(double lowest, double highest) {
    BufferedFile style(m_stage, m_temporary, m_style);
    style.text(qgisTerrainStyle("z_mean", lowest, highest));
    style.close();
}

void StyleBeside::commit() const {
    try {
        m_temporaries.commit(m_temporary, m_style);
    } catch (const Error&) {
        // The data this run has just put in place would otherwise stand without its style.
        for (const auto& file : m_created) {
            std::error_code ignored;
            fs::remove(file, ignored);
        }
        throw;
    }
}

} // namespace terratin::io::detail
