#pragma once
// terratin-bench --refine: the terrain refinement table.

#include "bench_options.hpp"

namespace terratin::bench {

/// Reads each DEM once (not timed), then times terratin::refine (no I/O: selection, insertion,
/// extraction, hole dropping and the error check) for each tolerance and thread count, median
/// of --runs runs, and prints points, triangles, achieved max error, RMSE, seconds, the
/// speed-up against 1 thread, and the peak resident memory growth of the call. Returns the exit
/// status. Throws terratin::Error when terratin-bench was built without terratin::io.
int runRefineBench(const BenchOptions& options);

} // namespace terratin::bench
