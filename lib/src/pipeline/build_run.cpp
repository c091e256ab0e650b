#include "build_run.hpp"

#include "gather_inputs.hpp"
#include "terratin/pipeline/build_option_table.hpp"
#include "terratin/triangulate/mesh_filter.hpp"

#include <ogr_spatialref.h>

#include <algorithm>
#include <utility>

namespace terratin::detail {

namespace {

bool isConstraintVertex(std::uint32_t source) {
    return source == kConstraintPointSource || source == kIntersectionSource;
}

// Each breakline's vertices, as points (LandXML writes them so; a vertex number would not
// survive dropping triangles).
std::vector<std::vector<Point3>> chainPoints(const ConstrainedTin& constrained,
                                             const TinMesh& mesh) {
    std::vector<std::vector<Point3>> lines;
    lines.reserve(constrained.chains.size());
    for (const std::vector<std::uint32_t>& chain : constrained.chains) {
        if (chain.size() < 2)
            continue;
        std::vector<Point3>& line = lines.emplace_back();
        for (const std::uint32_t vertex : chain)
            line.push_back(mesh.vertices[vertex]);
    }
    return lines;
}

// The per-half-edge flags of the triangles `drop` keeps, in order (dropTriangles keeps the
// kept triangles' order and corners).
void keepEdgesOfKeptTriangles(MeshArray<std::uint8_t>& edgeFlags,
                              const std::vector<std::uint8_t>& drop) {
    if (edgeFlags.empty())
        return;
    std::size_t kept = 0;
    for (std::size_t t = 0; t < drop.size(); ++t)
        if (drop[t] == 0) {
            std::copy_n(edgeFlags.begin() + static_cast<std::ptrdiff_t>(3 * t), 3,
                        edgeFlags.begin() + static_cast<std::ptrdiff_t>(3 * kept));
            ++kept;
        }
    edgeFlags.resize(3 * kept);
}

// The raster cell of every vertex, for the GeoPackage nodes layer: `cellOf(source)` is the
// row-major cell index of input point `source`.
std::vector<io::RasterCell> vertexCells(const TinMesh& mesh, std::uint64_t width,
                                        const std::function<std::uint64_t(std::uint32_t)>& cellOf) {
    std::vector<io::RasterCell> cells(mesh.vertexCount());
    for (std::size_t v = 0; v < cells.size(); ++v) {
        if (isConstraintVertex(mesh.sourceIndex[v])) {
            cells[v] = {-1, -1}; // a breakline's point or crossing: no cell
            continue;
        }
        const std::uint64_t cell = cellOf(mesh.sourceIndex[v]);
        cells[v] = {static_cast<std::int64_t>(cell / width),
                    static_cast<std::int64_t>(cell % width)};
    }
    return cells;
}

} // namespace

BuildRun::BuildRun(const BuildOptions& options, io::TinFormat format, ProgressCallback progress)
    : m_options(&options), m_progress(std::move(progress)),
      m_writeOptions(tinWriteOptions(options, format)) {
    for (std::size_t i = 0; i < options.inputs.size(); ++i)
        m_report.input += (i > 0 ? ", " : "") + options.inputs[i];
    m_report.output = (options.tilesDir.empty() ? options.output : options.tilesDir).string();
    m_report.format = std::string(io::tinFormatName(format));
}

ProgressCallback BuildRun::phase(double start, double share) const {
    return phaseProgress(m_progress, start, share);
}

void BuildRun::notify(const std::string& text) {
    detail::notify(*m_options, m_report, text);
}

BuildReport BuildRun::write(TinProduct product) {
    m_writeOptions.crsWkt = product.crsWkt;
    WholeFileSink sink(m_options->output, m_writeOptions);
    deliver(sink, 0, std::move(product.mesh), product.cells);
    return close(sink);
}

void BuildRun::deliver(TinSink& sink, std::size_t piece, TinMesh tin,
                       const VertexRasterCells& cells) {
    if (m_options->maxEdge) {
        const std::vector<std::uint8_t> drop = longEdgeTriangles(tin, *m_options->maxEdge);
        keepEdgesOfKeptTriangles(m_writeOptions.constrainedEdges, drop);
        m_report.longEdgeTriangles += dropTriangles(tin, drop);
    }
    std::vector<io::RasterCell> tinCells;
    if (m_options->nodes && cells.cellOf)
        tinCells = vertexCells(tin, cells.rasterWidth, cells.cellOf);
    sink.write(piece, std::move(tin), std::move(tinCells));
}

BuildReport BuildRun::close(TinSink& sink) {
    m_report.triangles = sink.triangles();
    const Stopwatch writeTime;
    const io::TinWriteResult written =
        sink.finish(phase(kReadShare + kTriangulateShare, kWriteShare));
    m_report.timings.write = writeTime.seconds();
    m_report.writeFeatures = written.features;
    m_report.writeRowSeconds = written.rowSeconds;
    m_report.writeIndexSeconds = written.indexSeconds;
    m_report.writeFeaturesPerSecond =
        m_report.timings.write > 0.0
            ? static_cast<double>(written.features) / m_report.timings.write
            : 0.0;
    m_report.timings.total = m_total.seconds();
    if (m_progress)
        m_progress(1.0, "done");
    return m_report;
}

void describeCrs(const std::string& wkt, BuildReport& report) {
    if (wkt.empty())
        return;
    OGRSpatialReference srs;
    if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE)
        return; // the writer will report an unusable CRS with context
    if (const char* name = srs.GetName())
        report.crsName = name;
    srs.AutoIdentifyEPSG();
    const char* authority = srs.GetAuthorityName(nullptr);
    const char* code = srs.GetAuthorityCode(nullptr);
    if (authority != nullptr && code != nullptr)
        report.crsCode = std::string(authority) + ":" + code;
}

bool hasConstraints(const BuildOptions& options) {
    return !options.breaklines.empty() || !options.clip.empty() || !options.erase.empty() ||
           !options.replace.empty();
}

std::size_t takeConstrainedOutput(ConstrainedTin& tin, const std::vector<std::uint8_t>& drop,
                                  io::TinWriteOptions& writeOptions) {
    writeOptions.constrainedEdges = std::move(tin.constrained);
    if (writeOptions.format == io::TinFormat::LandXml)
        writeOptions.breaklines = chainPoints(tin, tin.mesh);
    if (drop.empty())
        return 0;
    keepEdgesOfKeptTriangles(writeOptions.constrainedEdges, drop);
    const std::size_t removed = dropTriangles(tin.mesh, drop);
    if (tin.mesh.triangleCount() == 0)
        throw InvalidInputError("Build: no triangle is left inside the clip area and outside "
                                "the erase areas");
    return removed;
}

} // namespace terratin::detail
