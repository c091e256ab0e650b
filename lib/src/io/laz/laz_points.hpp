#pragma once
/// @file
/// The points of a LAZ file as the LAS reader gives them: decoded on several threads in
/// bounded memory (laz_point_runs.hpp), filtered by class, return and withheld flag as a LAS
/// file's are, in file order whatever the number of threads.

#include "../las_record_filter.hpp"
#include "laz_file.hpp"
#include "terratin/io/point_source.hpp"
#include "terratin/progress.hpp"

namespace terratin::io::laz {

/// Appends to `cloud` the points of `file` that `filter` keeps, counting the others in
/// `cloud.filteredOut`; decodes on `threads` threads (0: all hardware threads), only the
/// fields a TIN needs. `progress` is called after each round of chunks with the fraction of
/// points read; Cancelled when it returns false. InvalidInputError for a corrupt chunk.
void readLazPoints(const LazFile& file, const detail::LasRecordFilter& filter, unsigned threads,
                   const ProgressCallback& progress, PointCloud& cloud);

} // namespace terratin::io::laz
