#pragma once
/// @file
/// The batch method of Kohout & Kolingerova (section 3.3): K searching threads locate points
/// in the shared DAG without any lock and hand (point, node reached) to one specialised thread
/// through a bounded queue; the specialised thread completes each location from that node,
/// subdivides and legalises. Only the specialised thread modifies the DAG, so the result is
/// the same exact Delaunay triangulation the sequential code would build for the order in
/// which the points leave the queue.

#include "dag_triangulator.hpp"

#include <cstddef>
#include <span>

namespace terratin::detail {

/// How to run the batch method.
struct BatchSettings {
    /// Searching threads; the calling thread is the specialised one.
    unsigned searchers = 3;
    /// Capacity of the shared queue (rounded up to a power of two); the paper's Table 1
    /// found 1024 best for large inputs.
    std::size_t queueLength = 1024;
    /// The paper's footnote: a searcher that finds the queue full takes the oldest element,
    /// completes its location (work the specialised thread would otherwise do) and puts it
    /// back, instead of waiting idle.
    bool searchersHelpWhenFull = false;
    /// Searchers locate each point by a visibility walk from the leaf they found for their
    /// previous point (DagTriangulator::walk) instead of descending the DAG from the root.
    bool walk = false;
};

/// Counters that MethodDiagnostics (triangulate.hpp) reports and terratin-bench prints.
struct BatchStatistics {
    /// Elements whose location a searcher completed because the queue was full.
    std::size_t helpedLocations = 0;
};

/// Inserts `order` into `triangulator` with the batch method. Calls `progress` from the
/// calling thread only; throws Cancelled when it returns false, and rethrows any exception a
/// searcher hit, after every thread has stopped.
BatchStatistics insertWithBatchMethod(DagTriangulator& triangulator,
                                      std::span<const VertexId> order,
                                      const BatchSettings& settings,
                                      const ProgressCallback& progress);

} // namespace terratin::detail
