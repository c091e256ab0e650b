#pragma once
/// @file
/// The rows and R-tree of a TIN's GeoPackage layers, written through one SQLite connection
/// into tables that already exist: a new file's, or those just added to a user's file.

#include "../writer_support.hpp"
#include "gpkg_tin_layers.hpp"

#include "terratin/io/tin_writer.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace terratin::io::detail {

/// One layer's rows and index, in writing order.
struct GpkgLayerJob {
    std::string name;
    std::uint64_t features = 0;
    std::string_view rowMessage;
    std::function<void(SqliteConnection&, const GpkgFeatureTable&, const RowProgress&)> rows;
    std::function<std::vector<RtreeBox>()> boxes;
};

/// The layers `options` asks for: triangles, then nodes and edges when asked. The jobs refer
/// to `mesh` and `options`, which must outlive them.
std::vector<GpkgLayerJob> gpkgLayerJobs(const TinMesh& mesh, const TinWriteOptions& options);

/// Every job's rows, then every job's spatial index (when `spatialIndex`), with progress
/// over rows and then index entries. The caller holds the transaction. Returns the seconds
/// each part took.
TinWriteResult fillGpkgLayers(SqliteConnection& db, const TinMesh& mesh,
                              const std::vector<GpkgLayerJob>& jobs, bool spatialIndex,
                              const ProgressTicker& ticker);

} // namespace terratin::io::detail
