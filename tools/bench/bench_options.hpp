#pragma once
// Command-line parsing for `terratin-bench`: Boost.Program_options onto BenchOptions.

#include "distributions.hpp"

#include "terratin/triangulate/triangulate.hpp"

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace terratin::bench {

/// A command line that cannot be understood; terratin-bench exits with status 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A triangulation method the bench can ask for by name.
struct NamedMethod {
    std::string_view name;
    TriangulationMethod method;
};

/// The methods of this build of terratin::core, in table order: sequential, batch and, once
/// the library has it, circumcircle. Auto is left out: the bench names what it measures.
const std::vector<NamedMethod>& benchMethods();

/// The method called `name` (case-insensitive). Throws UsageError naming the methods there are.
NamedMethod parseMethod(std::string_view name);

/// What to measure.
struct BenchOptions {
    /// Requested point counts, ascending; Grid rounds each to a square.
    std::vector<std::size_t> sizes;
    std::vector<Distribution> distributions;
    std::vector<NamedMethod> methods;
    /// TriangulationOptions::threads values; the sequential method runs once, with 1.
    std::vector<unsigned> threads;
    /// Timed runs per configuration; the median is reported.
    unsigned runs = 5;
    /// Seed of the point sets and of the insertion order.
    std::uint64_t seed = 1;
    InsertionOrder order = InsertionOrder::Brio;
    /// Point location strategies, each measured for every method (DAG first).
    std::vector<PointLocation> locations{PointLocation::Dag, PointLocation::Walk};
    /// Batch method settings, passed through (0 searchers: the library chooses).
    unsigned searchers = 0;
    std::size_t queueLength = TriangulationOptions{}.queueLength;
    bool helpWhenFull = false;
    /// A peer run longer than this (seconds) ends that configuration's runs, and the peer is
    /// skipped at larger sizes of the same distribution: qhull's time explodes on cocircular
    /// input (GDAL on the arc), and a table should not take hours.
    double peerLimitSeconds = 10.0;
    bool runCgal = true;
    bool runGdal = true;
    /// Warm the memory each run will touch before timing it (warmFreeMemory).
    bool warmMemory = true;
    /// Comma-separated rows instead of the aligned table.
    bool csv = false;
    /// Terrain refinement table instead (refine_bench.cpp): real DEMs from `demDirectory`.
    bool refine = false;
    /// Output table instead (write_bench.cpp): every format end to end on real DEMs from
    /// `demDirectory`, against the GDAL + CGAL + OGR script, a plain OGR loop and SQLite's bound.
    bool write = false;
    /// --write: the output formats to time, by extension (gpkg fgb shp ply 2dm obj xml).
    std::vector<std::string> writeFormats{"gpkg", "fgb", "shp", "ply", "2dm", "obj", "xml"};
    std::string demDirectory = "../shared/dems";
    /// Whether --threads was given (the refinement table defaults to 1 and 2 threads).
    bool threadsGiven = false;
};

/// What the user asked for.
struct BenchCommand {
    enum class Kind { Run, Help };
    Kind kind = Kind::Run;
    std::string helpText;
    BenchOptions options;
};

/// Parses argv (without the program name). Throws UsageError with a one-line reason.
BenchCommand parseBenchCommandLine(const std::vector<std::string>& arguments);

} // namespace terratin::bench
