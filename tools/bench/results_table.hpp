#pragma once
// The bench's output: one row per configuration, as an aligned table or as CSV.

#include <cstddef>
#include <cstdio>
#include <optional>
#include <string>

namespace terratin::bench {

/// The median of one configuration's runs on one point set.
struct ResultRow {
    std::string distribution;
    /// Points generated (a square for the grid).
    std::size_t points = 0;
    /// A terratin method ("sequential", "batch", ...) or a peer ("cgal", "gdal").
    std::string method;
    /// terratin's point location ("dag", "walk"); empty for the peers.
    std::string locate;
    /// TriangulationOptions::threads asked for, and threads that ran in all.
    unsigned threadsRequested = 1;
    unsigned threadsUsed = 1;
    /// Batch method: searching threads, and locations they finished on a full queue.
    unsigned searchers = 0;
    std::size_t helpedLocations = 0;
    std::size_t triangles = 0;
    /// Runs made and the median of their wall-clock seconds; none when the configuration
    /// failed or was skipped, which `unmeasured` then says.
    unsigned runs = 0;
    std::optional<double> seconds;
    std::string unmeasured = "failed";
    /// Our sequential method's seconds (same point location) / these seconds, same points.
    std::optional<double> speedUp;
    /// TriangulationResult::historyBytes / points.
    std::optional<double> historyBytesPerPoint;
    /// Capacity of the TinMesh's four arrays, in bytes, / points.
    std::optional<double> meshBytesPerPoint;
    /// Median growth of the peak resident set during the call / points.
    std::optional<double> peakBytesPerPoint;
    /// These seconds / the peer's seconds, same points: below 1 means terratin is faster.
    std::optional<double> vsCgal;
    std::optional<double> vsGdal;
};

/// Writes rows to `stream` as they come, after a header; as an aligned table or as CSV.
class ResultTable {
public:
    ResultTable(std::FILE* stream, bool csv) : m_stream(stream), m_csv(csv) {}

    void printHeader();
    void printRow(const ResultRow& row);
    /// A blank line between distributions in the table; nothing in CSV.
    void printSeparator();

private:
    std::FILE* m_stream;
    bool m_csv;
};

} // namespace terratin::bench
