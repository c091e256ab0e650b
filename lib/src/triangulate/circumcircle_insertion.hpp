#pragma once
/// @file
/// The circum-circle method of Kohout & Kolingerova (section 3.4): every worker thread
/// locates, subdivides and legalises its own points in the shared DAG, waiting for the others
/// by a circumcircle test and taking every triangle it changes under an owner tag. The
/// synchronisation protocol, and why the result is exactly Delaunay, are described in
/// docs/algorithms.md ("The circum-circle method").

#include "dag_triangulator.hpp"

#include <cstddef>
#include <span>

namespace terratin::detail {

/// Counters that MethodDiagnostics (triangulate.hpp) reports and terratin-bench prints.
struct CircumcircleStatistics {
    /// Times a worker waited for another (geometric conflict or held triangle).
    std::size_t waits = 0;
    /// Deadlocks resolved by overriding another worker.
    std::size_t overrides = 0;
    /// Deadlocks resolved by a worker giving up its own attempt, which had changed nothing.
    std::size_t backOffs = 0;
    /// Edges left unchecked by overridden workers; repairs of the triangulation after
    /// overrides (repair_rendezvous.hpp) and the flips they made.
    std::size_t deferredEdges = 0;
    std::size_t repairs = 0;
    std::size_t repairFlips = 0;
};

/// Inserts `order` into `triangulator` with `workers` threads (clamped to 1 ..
/// OwnerTag::kMaxWorkers, 4094), while the calling thread watches them. `roundStarts` splits the
/// order into rounds (BRIO; {0} for one round): each worker inserts its own contiguous share of
/// every round in turn, so that with a spatially sorted round the workers stay far apart and rarely
/// conflict. With `walk`, each worker locates a point by a visibility walk from the triangles of
/// its previous one (DagTriangulator::walk) instead of descending the DAG from the root. Calls
/// `progress` from the calling thread only; throws Cancelled when it returns false and rethrows any
/// worker's exception, after every thread has stopped.
CircumcircleStatistics insertWithCircumcircleMethod(DagTriangulator& triangulator,
                                                    std::span<const VertexId> order,
                                                    std::span<const std::size_t> roundStarts,
                                                    unsigned workers, bool walk,
                                                    const ProgressCallback& progress);

} // namespace terratin::detail
