#pragma once
/// @file
/// The triangulation entry point of terratin::core: points in, Delaunay TIN out.

#include "terratin/geometry/point.hpp"
#include "terratin/progress.hpp"
#include "terratin/triangulate/point_set.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace terratin {

/// The order in which points are inserted.
enum class InsertionOrder {
    /// A uniformly random permutation: the paper's order.
    Random,
    /// Biased randomized insertion order: random rounds, each sorted along a Hilbert curve.
    /// Same expected complexity, far fewer cache misses in the DAG (several times faster on
    /// large inputs).
    Brio,
};

/// How the triangle containing a new point is found.
enum class PointLocation {
    /// Descent of the DAG history (the paper's structure; expected O(log n) per point).
    Dag,
    /// Visibility walk from the thread's previous point, on the current triangulation; no
    /// O(log n) guarantee, but with the BRIO order the walks are short and stay in cache.
    /// The sequential method then keeps no history at all (Bowyer-Watson insertion, the
    /// strip method's core); batch and circum-circle still build the DAG for their descents.
    Walk,
};

/// Which triangulator inserts the points.
enum class TriangulationMethod {
    /// One thread (Kohout & Kolingerova section 3.1).
    Sequential,
    /// Searching threads locate, one specialised thread subdivides and legalises (section 3.3).
    Batch,
    /// Every thread inserts, after testing the points other threads insert against the
    /// circumcircle of each triangle it touches (section 3.4). docs/algorithms.md ("The
    /// circum-circle method") describes it.
    Circumcircle,
    /// One vertical strip of the plane per thread, no history, always walks; the fastest
    /// method. docs/algorithms.md ("The strip method") describes it.
    Strips,
    /// The strip method (with one thread, a history-free sequential insertion); with the
    /// random order, whose walks would be long, the sequential method.
    Auto,
};

/// Most threads any parallel method (and the refiner) runs: far more than any machine's
/// hardware threads today (oversubscribed threads only wait for each other), and few enough
/// that starting and joining them all stays well under a second.
inline constexpr unsigned kMaxThreads = 1024;

/// Longest queue of the batch method, in entries (16 bytes each: 16 MiB). The queue only
/// has to absorb the searchers' bursts; the paper's runs used a few hundred entries.
inline constexpr std::size_t kMaxQueueLength = std::size_t{1} << 20;

/// How to triangulate. checkTriangulationOptions states the ranges.
struct TriangulationOptions {
    /// Seed of the random insertion order. Every seed gives the same triangles (cocircular ties
    /// are broken by the points alone); the same seed, method and thread count also number
    /// them the same way, except with the batch and circum-circle methods (see triangulate()).
    std::uint64_t seed = 1;
    InsertionOrder order = InsertionOrder::Brio;
    /// Which elevation survives for points sharing exactly the same (x, y).
    DuplicateZPolicy duplicateZ = DuplicateZPolicy::First;
    TriangulationMethod method = TriangulationMethod::Auto;
    /// How every method locates points (batch: its searching threads).
    PointLocation locate = PointLocation::Dag;
    /// Hardware threads to use, 0 to kMaxThreads; 0 means all
    /// (std::thread::hardware_concurrency(), at most kMaxThreads).
    unsigned threads = 0;
    /// Batch method: searching threads, 0 to kMaxThreads - 1 (one more thread inserts); 0
    /// chooses from the point and thread counts.
    unsigned searchers = 0;
    /// Batch method: capacity of the queue between searchers and the specialised thread,
    /// entries, 1 to kMaxQueueLength (rounded up to a power of two).
    std::size_t queueLength = 1024;
    /// Batch method: searchers finish queued locations instead of waiting on a full queue
    /// (the improvement in the paper's footnote).
    bool searchersHelpWhenQueueFull = false;
    /// Room left in the mesh's arrays for this many more vertices, and two triangles each, to
    /// be inserted later (insertConstraints, insertVertices): a full array grows by a copy of
    /// all of it. The room is address space until it is used.
    std::size_t spareVertices = 0;
    /// Fill TriangulationResult::diagnostics. The methods count either way (one increment
    /// per event, in thread-local counters); this only copies the counts into the result.
    bool collectDiagnostics = false;
};

/// Wall-clock seconds of the triangulation's phases.
struct TriangulationPhases {
    /// Validation, duplicate merging, local origin.
    double prepare = 0.0;
    /// The (BRIO or random) insertion order.
    double order = 0.0;
    /// Location, subdivision and legalisation of every point (the parallel part).
    double insert = 0.0;
    /// Turning the DAG's leaves into the TinMesh arrays.
    double extract = 0.0;
};

/// What a method did on its way, for research and tuning (terratin-bench prints it):
/// counters of the paper's mechanisms, not properties of the TIN. A counter stays 0 where the
/// method that ran has no such mechanism.
struct MethodDiagnostics {
    /// Nodes in the point-location history (triangles ever created); 0 for the history-free
    /// insertion (the strip method, the sequential walk).
    std::size_t historyNodes = 0;
    /// Batch method: searching threads, and locations they completed on a full queue.
    unsigned searchers = 0;
    std::size_t helpedLocations = 0;
    /// Circum-circle method: waits for another thread, deadlocks resolved by an override or
    /// by a thread giving up its own unchanged attempt, edges an overridden thread left
    /// unchecked, and the repairs after overrides with the flips they made.
    std::size_t waits = 0;
    std::size_t overrides = 0;
    std::size_t backOffs = 0;
    std::size_t deferredEdges = 0;
    std::size_t repairs = 0;
    std::size_t repairFlips = 0;
    /// Strip method: points left to the merged levels (near a strip boundary).
    std::size_t deferredPoints = 0;
};

/// A TIN and what it took to build it.
struct TriangulationResult {
    TinMesh mesh;
    std::size_t inputPoints = 0;
    /// Input points merged into another with exactly the same (x, y).
    std::size_t duplicatePoints = 0;
    /// Bytes reserved for the method's own structure besides the mesh: the point-location
    /// history (DAG), or the history-free insertion's working mesh.
    std::size_t historyBytes = 0;
    /// The method that ran (never Auto) and with how many threads in all.
    TriangulationMethod method = TriangulationMethod::Sequential;
    unsigned threads = 1;
    TriangulationPhases seconds;
    /// Only when TriangulationOptions::collectDiagnostics asked for it.
    std::optional<MethodDiagnostics> diagnostics;
};

/// Throws InvalidInputError, naming the option and its range, when `threads`, `searchers` or
/// `queueLength` is outside the range its documentation states. triangulate() calls it first;
/// a caller that maps user input onto the options (the CLI) calls it to refuse bad values
/// before reading anything.
void checkTriangulationOptions(const TriangulationOptions& options);

/// "sequential", "batch", "circumcircle", "strips" or "auto".
const char* toString(TriangulationMethod method);

/// Delaunay triangulation of `points` (x, y in any planar units; z carried along).
///
/// Postconditions: the triangles cover exactly the convex hull of the distinct points; every
/// distinct point is a vertex; across every interior edge the opposite vertex is never strictly
/// inside a triangle's circumcircle, decided with exact predicates, so the result is exactly
/// Delaunay. Among cocircular points (every cell of a grid) the diagonal is chosen by the four
/// points alone (predicates::incircleTieBroken), so the set of triangles, each as its three
/// input points, is the same for every method, thread count, seed and insertion order. The
/// numbering of vertices and triangles, and which corner of a triangle comes first, follow the
/// insertion: they may differ between methods, thread counts and seeds, and with the batch and
/// circum-circle methods, whose threads' timing orders the insertions, between runs.
/// Throws InvalidInputError (options out of range, see checkTriangulationOptions;
/// non-finite values, fewer than three non-collinear points, too many points) and Cancelled
/// when `progress` returns false; every method, the parallel ones included, polls `progress`
/// a few times a second from the calling thread and stops within a fraction of a second,
/// however many threads run.
/// Complexity: expected O(n log n) time, O(n) memory (the DAG methods: about 9 history nodes
/// of 32 bytes per point besides the mesh).
TriangulationResult triangulate(std::span<const Point3> points,
                                const TriangulationOptions& options = {},
                                const ProgressCallback& progress = {});

} // namespace terratin
