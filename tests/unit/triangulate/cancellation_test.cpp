// Hostile conditions: the parallel methods with more threads than cores must stop when the
// progress callback asks them to (Ctrl-C in the CLI), from every waiting loop, and refuse
// thread, searcher and queue counts that make no sense (zero, wrapped, over the bounds). No
// timing is asserted: a method that ignored the cancel would run to the end and fail the
// expectations (or, stuck in a wait, hit the test's timeout).

#include "terratin/triangulate/triangulate.hpp"

#include "point_distributions.hpp"
#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <string>
#include <thread>

namespace terratin {
namespace {

using test::Distribution;

// Large enough that no method finishes before the watching thread's first report (20 ms),
// small enough for ThreadSanitizer.
constexpr std::size_t kPoints = 200000;

unsigned oversubscribedThreads() {
    return 4 * std::max(1U, std::thread::hardware_concurrency());
}

struct CancelCase {
    TriangulationMethod method;
    PointLocation locate;
    /// Calls answered true before the one that cancels.
    int callsBeforeCancel;
};

std::string caseName(const ::testing::TestParamInfo<CancelCase>& info) {
    return std::string(toString(info.param.method)) +
           (info.param.locate == PointLocation::Walk ? "_walk" : "_dag") + "_after" +
           std::to_string(info.param.callsBeforeCancel);
}

class ParallelCancellation : public ::testing::TestWithParam<CancelCase> {};

TEST_P(ParallelCancellation,
       ThrowsCancelledAndStopsReporting_WhenCallbackCancelsWithThreadsAboveCores) {
    const CancelCase param = GetParam();
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, kPoints, 22);
    TriangulationOptions options;
    options.method = param.method;
    options.locate = param.locate;
    options.threads = oversubscribedThreads();
    // Batch: far more searchers than cores, a short queue: the inserting thread and the
    // searchers spend most of their time waiting on each other.
    options.searchers = options.threads;
    options.queueLength = 4;
    int calls = 0;
    int callsAfterCancel = 0;
    bool cancelled = false;
    const ProgressCallback progress = [&](double fraction, std::string_view) {
        EXPECT_GE(fraction, 0.0);
        EXPECT_LE(fraction, 1.0);
        if (cancelled) {
            ++callsAfterCancel;
            return false;
        }
        cancelled = ++calls > param.callsBeforeCancel;
        return !cancelled;
    };
    EXPECT_THROW(triangulate(points, options, progress), Cancelled);
    EXPECT_TRUE(cancelled);
    EXPECT_EQ(callsAfterCancel, 0) << "the run went on reporting after the cancel";
}

INSTANTIATE_TEST_SUITE_P(
    Methods, ParallelCancellation,
    ::testing::Values(CancelCase{TriangulationMethod::Batch, PointLocation::Dag, 0},
                      CancelCase{TriangulationMethod::Batch, PointLocation::Walk, 2},
                      CancelCase{TriangulationMethod::Circumcircle, PointLocation::Dag, 0},
                      CancelCase{TriangulationMethod::Circumcircle, PointLocation::Walk, 2},
                      CancelCase{TriangulationMethod::Strips, PointLocation::Walk, 0},
                      CancelCase{TriangulationMethod::Strips, PointLocation::Walk, 2}),
    caseName);

// The cancel of a run whose threads wait for each other on exactly cocircular points (the
// circum-circle method's deadlock detection and repairs, the batch queue's full waits).
TEST(ParallelCancellation, StopsEveryMethod_WhenCancelledOnCocircularGrid) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Grid, kPoints, 3);
    for (const TriangulationMethod method :
         {TriangulationMethod::Batch, TriangulationMethod::Circumcircle,
          TriangulationMethod::Strips}) {
        TriangulationOptions options;
        options.method = method;
        options.threads = oversubscribedThreads();
        bool cancelled = false;
        const ProgressCallback progress = [&](double, std::string_view) {
            cancelled = true;
            return false;
        };
        EXPECT_THROW(triangulate(points, options, progress), Cancelled) << toString(method);
        EXPECT_TRUE(cancelled) << toString(method);
    }
}

// A callback that never cancels sees every method through, oversubscribed, and the result is
// still exactly what the sequential method gives (vertex count; the invariants are the other
// suites' business).
TEST(ParallelCancellation, CompletesEveryMethod_WhenCallbackNeverCancels) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, 20000, 9);
    for (const TriangulationMethod method :
         {TriangulationMethod::Batch, TriangulationMethod::Circumcircle,
          TriangulationMethod::Strips}) {
        TriangulationOptions options;
        options.method = method;
        options.threads = oversubscribedThreads();
        double last = 0.0;
        const ProgressCallback progress = [&](double fraction, std::string_view) {
            last = fraction;
            return true;
        };
        const TriangulationResult result = triangulate(points, options, progress);
        EXPECT_EQ(result.mesh.vertexCount(), points.size()) << toString(method);
        EXPECT_EQ(last, 1.0) << toString(method);
    }
}

// Queue lengths, searcher and thread counts out of range (a wrapped "-1" included) are refused
// before anything runs, with a message that names the quantity (not a command-line flag); the
// bounds themselves are accepted.
TEST(TriangulationOptionsCheck, RefusesCountsOutOfRange_D2_D3_D4_D12) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, 100, 1);
    const auto expectRefused = [&](const TriangulationOptions& options, const std::string& word) {
        try {
            checkTriangulationOptions(options);
            ADD_FAILURE() << "accepted; expected a message about " << word;
        } catch (const InvalidInputError& error) {
            EXPECT_NE(std::string(error.what()).find(word), std::string::npos) << error.what();
            EXPECT_EQ(std::string(error.what()).find("--"), std::string::npos) << error.what();
        }
        EXPECT_THROW(triangulate(points, options), InvalidInputError);
    };
    TriangulationOptions options;
    options.queueLength = 0;
    expectRefused(options, "queue length");
    options.queueLength = kMaxQueueLength + 1;
    expectRefused(options, "queue length");
    options.queueLength = std::numeric_limits<std::size_t>::max(); // "-1" wrapped
    expectRefused(options, "queue length");
    options = {};
    options.searchers = kMaxThreads;
    expectRefused(options, "searching threads");
    options = {};
    options.threads = kMaxThreads + 1;
    expectRefused(options, "thread count");
    options.threads = std::numeric_limits<unsigned>::max();
    expectRefused(options, "thread count");

    // The bounds themselves are accepted.
    options = {};
    options.threads = kMaxThreads;
    options.searchers = kMaxThreads - 1;
    options.queueLength = kMaxQueueLength;
    EXPECT_NO_THROW(checkTriangulationOptions(options));
    options.queueLength = 1;
    options.threads = 0;
    options.searchers = 0;
    EXPECT_NO_THROW(checkTriangulationOptions(options));
}

} // namespace
} // namespace terratin
