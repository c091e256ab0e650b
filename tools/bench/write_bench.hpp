#pragma once
// terratin-bench --write: end-to-end DEM -> file runs of every output format, against the
// GDAL + CGAL + OGR script, a plain OGR loop and the SQLite bound.

#include "bench_options.hpp"

namespace terratin::bench {

/// Mt Hood at full resolution in every format, and N44W072 at --max-error 1 as a GeoPackage,
/// each configuration once per round for --runs rounds, interleaved; prints medians of the
/// whole run and of its write phase, features per second, peak resident growth and the ratios
/// to the peers. Returns the exit status. Throws terratin::Error when built without
/// terratin::io.
int runWriteBench(const BenchOptions& options);

} // namespace terratin::bench
