#include "breaklines.hpp"
#include "builds.hpp"
#include "gather_inputs.hpp"
#include "terratin/constrain/constrained_validation.hpp"
#include "terratin/triangulate/mesh_validation.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <algorithm>
#include <future>
#include <optional>
#include <utility>

namespace terratin::detail {

namespace {

// The triangulation's figures in the report.
void reportTriangulation(const TriangulationResult& triangulation, BuildReport& report) {
    report.duplicates = triangulation.duplicatePoints;
    report.vertices = triangulation.mesh.vertexCount();
    report.triangles = triangulation.mesh.triangleCount();
    report.method = toString(triangulation.method);
    report.threads = triangulation.threads;
    report.historyBytesPerPoint = static_cast<double>(triangulation.historyBytes) /
                                  static_cast<double>(std::max<std::uint64_t>(report.points, 1));
}

// The constraint layers, read beside the inputs, with z from the inputs' cells where they are
// one raster's.
std::optional<ConstraintSources> constraintSources(BuildRun& run,
                                                   std::future<ConstraintLayers>& layers,
                                                   const GatheredInputs& gathered) {
    if (!hasConstraints(run.options()))
        return std::nullopt;
    const Stopwatch constrainTime;
    const std::optional<HeightGrid> dem =
        cellSurface(gathered, run.options().triangulation.threads);
    ConstraintSources sources = readConstraintSources(layers.get(), run.options(), gathered.crsWkt,
                                                      dem ? &*dem : nullptr, run.report());
    run.report().timings.constrain = constrainTime.seconds();
    return sources;
}

void validate(BuildRun& run, const TinMesh& mesh, const std::optional<ConstrainedBuild>& tin) {
    const Stopwatch validateTime;
    if (tin)
        checkValid(validateConstrainedDelaunay(tin->tin), "constrained Delaunay");
    else
        checkValid(validateDelaunay(mesh), "Delaunay");
    run.report().validated = true;
    run.report().timings.validate = validateTime.seconds();
}

} // namespace

BuildReport buildPointTin(BuildRun& run) {
    const BuildOptions& options = run.options();
    BuildReport& report = run.report();
    // The constraint layers are read while the inputs are.
    std::future<ConstraintLayers> constraintLayers;
    if (hasConstraints(options))
        constraintLayers = startReadingConstraintLayers(options);
    const Stopwatch readTime;
    GatheredInputs gathered = gatherInputs(options, report, run.phase(0.0, kReadShare));
    describeCrs(gathered.crsWkt, report);
    report.timings.read = readTime.seconds();

    const Stopwatch triangulateTime;
    std::optional<ConstraintSources> sources = constraintSources(run, constraintLayers, gathered);
    TriangulationOptions triangulationOptions = options.triangulation;
    if (sources)
        triangulationOptions.spareVertices = sources->spareVertices();
    TriangulationResult triangulation = triangulate(gathered.points, triangulationOptions,
                                                    run.phase(kReadShare, kTriangulateShare));
    gathered.points = {}; // the mesh holds its own copy of the vertices
    countDuplicatesPerInput(gathered.offsets, triangulation.mesh.sourceIndex, report);
    reportTriangulation(triangulation, report);
    std::optional<ConstrainedBuild> constrained;
    if (sources) {
        const Stopwatch constrainTime;
        // The constraints' insertion polls the progress, so that a cancel reaches it.
        constrained =
            addConstraints(std::move(triangulation.mesh), options, report, std::move(*sources),
                           run.phase(kReadShare + kTriangulateShare, 0.0));
        report.timings.constrain += constrainTime.seconds();
        report.vertices = constrained->tin.mesh.vertexCount();
    }
    report.timings.triangulate = triangulateTime.seconds();
    if (options.validate)
        validate(run, triangulation.mesh, constrained);

    TinProduct product{std::move(triangulation.mesh), gathered.crsWkt, {{}, gathered.rasterWidth}};
    if (constrained) {
        report.areaTriangles =
            takeConstrainedOutput(constrained->tin, constrained->outsideArea, run.writeOptions());
        product.mesh = std::move(constrained->tin.mesh);
        report.vertices = product.mesh.vertexCount();
    }
    // Row and column mean something for one raster's cells only.
    if (gathered.rasterWidth != 0)
        product.cells.cellOf = [cellIndex = std::move(gathered.cellIndex)](std::uint32_t source) {
            return static_cast<std::uint64_t>(cellIndex[source]);
        };
    return run.write(std::move(product));
}

} // namespace terratin::detail
