// Builds a simplified TIN of a DEM into a GeoPackage with terratin::io, as
// `terratin build DEM -o OUT.gpkg --max-error 1 --overwrite` does, and prints the report.
//   dem_to_gpkg DEM OUT.gpkg

#include "terratin/error.hpp"
#include "terratin/pipeline/build_pipeline.hpp"

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: dem_to_gpkg DEM OUT.gpkg\n");
        return 2;
    }
    terratin::BuildOptions options;
    options.inputs = {argv[1]}; // anything GDAL opens as a raster
    options.output = argv[2];   // the format follows the extension
    options.overwrite = true;
    // Keep only the vertices needed for every cell to be within 1 z unit of the TIN.
    options.refine = terratin::RefineOptions{};
    options.refine->maxError = 1.0;
    try {
        // Reads, triangulates and writes (atomically: a failed run leaves no output).
        const terratin::BuildReport report = terratin::runBuild(options);
        std::printf("%s%s\n", terratin::toInputSummary(report).c_str(),
                    terratin::toSummaryLine(report).c_str());
        std::printf("layer tin: %llu triangles\n",
                    static_cast<unsigned long long>(report.triangles));
    } catch (const terratin::Error& error) {
        // Every failure is a terratin::Error whose message names the stage and the file.
        std::fprintf(stderr, "dem_to_gpkg: %s\n", error.what());
        return 1;
    }
    return 0;
}
