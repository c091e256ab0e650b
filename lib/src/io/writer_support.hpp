#pragma once
/// @file
/// Pieces every TIN writer shares: progress with cancellation, the CRS as the mesh formats
/// describe it.

#include "terratin/geometry/point.hpp"
#include "terratin/io/tin_format.hpp"
#include "terratin/progress.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace terratin::io::detail {

/// Items (features, vertices, faces) between two progress reports: frequent enough for a
/// responsive Ctrl-C (a few tenths of a second), rare enough that the callback costs nothing
/// measurable.
inline constexpr std::uint64_t kProgressInterval = 65'536;

/// Calls `progress` (when set); throws Cancelled "<stage>: cancelled; '<output>' was not
/// written" when it returns false.
void reportProgress(std::string_view stage, const ProgressCallback& progress, double fraction,
                    std::string_view message, const std::filesystem::path& output);

/// Progress over `total` items mapped onto [start, start + share] of the writer's range.
class ProgressTicker {
public:
    ProgressTicker(std::string_view stage, ProgressCallback progress, std::filesystem::path output,
                   double start, double share, std::uint64_t total)
        : m_stage(stage), m_progress(std::move(progress)), m_output(std::move(output)),
          m_start(start), m_share(share), m_total(total == 0 ? 1 : total) {}

    /// Reports when `done` is a multiple of kProgressInterval (so the first call, with 0, does).
    void tick(std::uint64_t done, std::string_view message) const {
        if (done % kProgressInterval == 0)
            report(done, message);
    }
    /// Reports the whole range done.
    void reportDone(std::string_view message) const { report(m_total, message); }
    void report(std::uint64_t done, std::string_view message) const {
        reportProgress(m_stage, m_progress,
                       m_start + m_share * static_cast<double>(done) / static_cast<double>(m_total),
                       message, m_output);
    }

private:
    std::string m_stage;
    ProgressCallback m_progress;
    std::filesystem::path m_output;
    double m_start;
    double m_share;
    std::uint64_t m_total;
};

/// The CRS as the mesh formats record it.
struct CrsSummary {
    /// "NAD83 / UTM zone 10N"; empty when there is no CRS.
    std::string name;
    /// "26910" when the CRS is identified as an EPSG code, else empty.
    std::string epsgCode;
    /// The WKT on one line (WKT1 when GDAL can export it, for the widest readership).
    std::string wkt;
    /// Horizontal unit: "metre", "US survey foot", "foot"... as the CRS names it; "metre" when
    /// there is no CRS.
    std::string linearUnitName = "metre";
    /// Metres per horizontal unit.
    double metresPerUnit = 1.0;

    [[nodiscard]] bool empty() const { return wkt.empty(); }
};

/// Parses `wkt` (empty: no CRS). Throws CrsError "<stage>: the output CRS is not valid WKT".
CrsSummary summariseCrs(std::string_view stage, const std::string& wkt);

/// The stage a writer of `format` starts its messages with ("PlyWriter", "OgrTinWriter"...).
std::string_view writerStage(TinFormat format);

/// What messages that list formats call `format` ("GeoPackage", "Shapefile", "PLY"); its row
/// of the format table (tin_format.cpp) says.
std::string_view formatTitle(TinFormat format);

} // namespace terratin::io::detail

namespace terratin::io::detail {

/// What the mesh writers record beside the mesh itself.
struct MeshFileInfo {
    /// Mesh / surface / object name (the layer name).
    std::string name = "tin";
    CrsSummary crs;
    std::string softwareVersion;
    /// LandXML: the breaklines (TinWriteOptions::breaklines); null or empty for none.
    const std::vector<std::vector<Point3>>* breaklines = nullptr;
};

} // namespace terratin::io::detail
