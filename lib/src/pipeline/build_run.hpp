#pragma once
/// @file
/// BuildRun: one build's state, which every producer reads and fills (the options, the
/// writers' options, the report, the progress and the clock), and the tail every build shares,
/// written once: each piece of the TIN (the whole TIN, or a tile) has its long edges dropped
/// and its nodes' raster cells found on its way into a sink (tin_sink.hpp: the whole file, the
/// streamed tiles, a directory of tiles), and closing the sink finishes the report. The
/// producers (builds.hpp) hand a whole TIN to write(), and a tiled one's tiles to deliver().

#include "../stopwatch.hpp"
#include "tin_sink.hpp"

#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/error.hpp"
#include "terratin/io/tin_writer.hpp"
#include "terratin/pipeline/build_pipeline.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace terratin::detail {

/// Share of the whole run each phase gets on the progress bar, roughly their usual cost.
inline constexpr double kReadShare = 0.1;
inline constexpr double kTriangulateShare = 0.4;
inline constexpr double kWriteShare = 0.5;

/// Where the vertices of a TIN lie in its raster, for the node layer's row and column: the
/// row-major raster cell of input point `source` (a vertex's sourceIndex) in a raster
/// `rasterWidth` cells wide. Unset when the vertices are no one raster's cells (point clouds,
/// several rasters).
struct VertexRasterCells {
    std::function<std::uint64_t(std::uint32_t source)> cellOf;
    std::uint64_t rasterWidth = 0;
};

/// A whole TIN, as a producer hands it to write().
struct TinProduct {
    TinMesh mesh;
    /// The CRS of the vertices, WKT; empty for none.
    std::string crsWkt;
    VertexRasterCells cells;
};

class BuildRun {
public:
    /// The run of `options`, whose checks have passed, writing `format`.
    BuildRun(const BuildOptions& options, io::TinFormat format, ProgressCallback progress);

    [[nodiscard]] const BuildOptions& options() const { return *m_options; }
    [[nodiscard]] BuildReport& report() { return m_report; }
    [[nodiscard]] io::TinWriteOptions& writeOptions() { return m_writeOptions; }
    [[nodiscard]] const ProgressCallback& progress() const { return m_progress; }
    /// The progress of a phase from `start` of the whole run for `share` of it.
    [[nodiscard]] ProgressCallback phase(double start, double share) const;
    /// A notice in the report (and to options.notice).
    void notify(const std::string& text);

    /// The whole TIN as the one piece of a WholeFileSink, in product.crsWkt, delivered and
    /// closed. Returns the finished report.
    BuildReport write(TinProduct product);
    /// Piece `piece` of the TIN into `sink`, after the tail every piece shares: its long edges
    /// dropped (options.maxEdge; the constrained edges' flags kept in step, for a whole TIN)
    /// and, with a nodes layer, its vertices' raster cells.
    void deliver(TinSink& sink, std::size_t piece, TinMesh tin, const VertexRasterCells& cells);
    /// After the last piece: the sink finished, the report given the sink's triangles, the
    /// write phase's figures and the total; the last progress call.
    BuildReport close(TinSink& sink);

private:
    const BuildOptions* m_options;
    ProgressCallback m_progress;
    BuildReport m_report;
    io::TinWriteOptions m_writeOptions;
    Stopwatch m_total;
};

/// The CRS's name and EPSG code in `report` (nothing for an empty or unreadable WKT).
void describeCrs(const std::string& wkt, BuildReport& report);

/// Throws when `validation` found a problem (MeshValidation or ConstrainedValidation).
template <class Validation> void checkValid(const Validation& validation, const char* what) {
    if (!validation.ok())
        throw Error(std::string("Validation: the mesh is not an exact ") + what +
                    " triangulation: " +
                    (validation.problems.empty() ? std::string("unknown problem")
                                                 : validation.problems.front()));
}

/// Whether the build has breaklines or clip, erase or replace areas.
bool hasConstraints(const BuildOptions& options);

/// The constrained TIN as the writers take it: its constrained edges and, for LandXML (the
/// one format that writes them), its breaklines go into `writeOptions` (the breaklines before
/// any triangle is dropped), and the triangles `drop` marks (none when empty) are removed.
/// Returns how many were removed; InvalidInputError when none is left.
std::size_t takeConstrainedOutput(ConstrainedTin& tin, const std::vector<std::uint8_t>& drop,
                                  io::TinWriteOptions& writeOptions);

} // namespace terratin::detail
