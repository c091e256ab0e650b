#pragma once
/// @file
/// The circum-circle method of Kohout & Kolingerova (section 3.4): every worker thread
/// locates, subdivides and legalises its own points in the shared DAG.
///
/// Synchronisation, as the paper describes it, with the additions that make it exact:
/// - The pool of tested points: each worker publishes the point it is inserting. Before a
///   worker touches a triangle it tests the other workers' points against that triangle's
///   circumcircle; while one lies inside, that worker will (or may) need the triangle, so the
///   tester waits, yielding.
/// - Exclusive access: a worker also takes the triangle (an atomic owner tag, one
///   compare-and-swap) before reading its neighbours or changing it, and holds everything it
///   took until its point is inserted (two-phase locking). The paper's geometric test alone
///   cannot see a thread that activates a point just after the test; the tag closes that gap,
///   so each insertion is atomic with respect to the others.
/// - Deadlock detection in a short critical section: before waiting for worker B, worker A
///   records it and follows the chain of waits from B; if it leads back to A, A does not wait.
///   If A has changed nothing yet (it has not subdivided), it steps aside: it gives up what it
///   holds, withdraws its point until the worker it would have waited for has finished its
///   own, and starts the point again.
///   Otherwise it overrides, as the paper does: it ignores the test (taking the triangle, from
///   B if B holds it) and sets B's override flag.
/// - Re-validation by the overridden worker: when B wakes up and finds its flag, it gives up
///   what it holds. Before its subdivision nothing was changed and it simply starts the point
///   again; during legalisation its remaining unchecked edges ("swaps left unprocessed" in
///   the paper) are counted and given up. Every override asks for a repair: the workers meet
///   between two points and the leaves created since the override began are made Delaunay
///   again (repair_rendezvous.hpp), so the result is always exactly Delaunay (the paper
///   accepted a few wrong triangles).

#include "dag_triangulator.hpp"

#include <cstddef>
#include <span>

namespace terratin::detail {

/// Counters for the benchmark and the closing notes.
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

/// Inserts `order` into `triangulator` with `workers` threads (the calling thread is one of
/// them; at most 4094). `roundStarts` splits the order into rounds (BRIO; {0} for one round): each
/// worker inserts its own contiguous share of every round in turn, so that with a spatially sorted
/// round the workers stay far apart and rarely conflict. With `walk`, each worker locates a
/// point by a visibility walk from the triangles of its previous one (DagTriangulator::walk)
/// instead of descending the DAG from the root. Calls `progress` from the calling
/// thread only; throws Cancelled when it returns false and rethrows any worker's exception,
/// after every thread has stopped.
CircumcircleStatistics insertWithCircumcircleMethod(DagTriangulator& triangulator,
                                                    std::span<const VertexId> order,
                                                    std::span<const std::size_t> roundStarts,
                                                    unsigned workers, bool walk,
                                                    const ProgressCallback& progress);

} // namespace terratin::detail
