// The scheduler of a refinement level's strips and pairs: every task runs once, never before
// the tasks it depends on, on any number of threads; a failing task or a stop ends the run
// without a hang. The plan of a level: its strips and pairs, and what each pair waits for.

#include "../parallel/round_workers.hpp"
#include "level_tasks.hpp"
#include "task_graph.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace terratin::detail {
namespace {

TEST(TaskGraph, RunsEveryTaskOnceAfterItsDependencies) {
    std::mt19937 random(7);
    for (const unsigned threads : {1U, 2U, 4U}) {
        RoundWorkers workers(threads);
        for (int trial = 0; trial < 50; ++trial) {
            // A random DAG: each task depends on a few earlier ones.
            TaskGraph graph;
            std::vector<std::pair<std::size_t, std::size_t>> edges;
            const std::size_t count = 1 + random() % 40;
            for (std::size_t task = 0; task < count; ++task) {
                graph.add();
                for (int d = 0; d < 3 && task > 0; ++d) {
                    const std::size_t dependency = random() % task;
                    graph.after(task, dependency);
                    edges.emplace_back(task, dependency);
                }
            }
            std::vector<std::atomic<int>> runs(count);
            std::vector<std::atomic<int>> finishedAt(count);
            std::atomic<int> clock{0};
            std::atomic<bool> dependencyLate{false};
            const std::atomic<bool> stop{false};
            graph.run(workers, stop, [&](std::size_t task, unsigned) {
                for (const auto& [later, earlier] : edges)
                    if (later == task && runs[earlier].load() == 0)
                        dependencyLate = true;
                ++runs[task];
                finishedAt[task] = ++clock;
            });
            for (std::size_t task = 0; task < count; ++task)
                EXPECT_EQ(runs[task].load(), 1) << "task " << task;
            EXPECT_FALSE(dependencyLate.load());
            for (const auto& [later, earlier] : edges)
                EXPECT_LT(finishedAt[earlier].load(), finishedAt[later].load());
        }
    }
}

TEST(TaskGraph, ReadyTasksStartInTheOrderAdded) {
    RoundWorkers workers(1);
    TaskGraph graph;
    for (int task = 0; task < 6; ++task)
        graph.add();
    graph.after(0, 5); // 0 waits for 5: 1, 2, 3, 4, 5, then 0
    std::vector<std::size_t> order;
    const std::atomic<bool> stop{false};
    graph.run(workers, stop, [&](std::size_t task, unsigned) { order.push_back(task); });
    EXPECT_EQ(order, (std::vector<std::size_t>{1, 2, 3, 4, 5, 0}));
}

TEST(TaskGraph, AFailingTaskEndsTheRunWithItsException) {
    for (const unsigned threads : {1U, 2U, 3U}) {
        RoundWorkers workers(threads);
        TaskGraph graph;
        for (int task = 0; task < 20; ++task)
            graph.add();
        for (std::size_t task = 11; task < 20; ++task)
            graph.after(task, 10); // never start: task 10 fails
        std::atomic<int> ran{0};
        const std::atomic<bool> stop{false};
        EXPECT_THROW(graph.run(workers, stop,
                               [&](std::size_t task, unsigned) {
                                   if (task == 10)
                                       throw std::runtime_error("task 10");
                                   ++ran;
                               }),
                     std::runtime_error);
        EXPECT_LE(ran.load(), 10);
    }
}

TEST(TaskGraph, StopLetsNoFurtherTaskStart) {
    for (const unsigned threads : {1U, 2U, 4U}) {
        RoundWorkers workers(threads);
        TaskGraph graph;
        for (int task = 0; task < 30; ++task)
            graph.add();
        for (std::size_t task = 1; task < 30; ++task)
            graph.after(task, task - 1); // a chain: one task at a time
        std::atomic<bool> stop{false};
        std::atomic<int> ran{0};
        graph.run(workers, stop, [&](std::size_t task, unsigned) {
            ++ran;
            if (task == 4)
                stop = true;
        });
        EXPECT_EQ(ran.load(), 5);
    }
}

TEST(LevelPlan, StripsWithMostCandidatesFirst_ThenEvenPairs_ThenOddPairs) {
    const std::vector<std::size_t> candidates{5, 9, 1, 9, 3};
    LevelPlan plan = planLevel(candidates);
    ASSERT_EQ(plan.tasks.size(), 9U);
    RoundWorkers workers(1);
    const std::atomic<bool> stop{false};
    std::vector<LevelTask> started;
    plan.graph.run(workers, stop,
                   [&](std::size_t task, unsigned) { started.push_back(plan.tasks[task]); });
    const std::vector<LevelTask> expected{
        LevelTask::strip(1), LevelTask::strip(3), LevelTask::strip(0),
        LevelTask::strip(4), LevelTask::strip(2), LevelTask::pair(0),
        LevelTask::pair(2),  LevelTask::pair(1),  LevelTask::pair(3)};
    EXPECT_EQ(started, expected);
}

TEST(LevelPlan, PairsRunAfterTheirStrips_AndOddPairsAfterThePairsBeside) {
    for (const std::size_t strips : {1U, 2U, 3U, 6U, 7U}) {
        const std::vector<std::size_t> candidates(strips, 1);
        LevelPlan plan = planLevel(candidates);
        ASSERT_EQ(plan.tasks.size(), 2 * strips - 1);
        RoundWorkers workers(4);
        const std::atomic<bool> stop{false};
        std::atomic<int> clock{0};
        std::vector<std::atomic<int>> stripDone(strips);
        std::vector<std::atomic<int>> pairStarted(strips);
        std::vector<std::atomic<int>> pairDone(strips);
        plan.graph.run(workers, stop, [&](std::size_t task, unsigned) {
            const LevelTask level = plan.tasks[task];
            if (level.isPair()) {
                pairStarted[level.first()] = ++clock;
                pairDone[level.first()] = ++clock;
            } else {
                stripDone[level.first()] = ++clock;
            }
        });
        for (std::size_t k = 0; k + 1 < strips; ++k) {
            EXPECT_LT(stripDone[k].load(), pairStarted[k].load()) << "pair " << k;
            EXPECT_LT(stripDone[k + 1].load(), pairStarted[k].load()) << "pair " << k;
            if (k % 2 == 1) {
                EXPECT_LT(pairDone[k - 1].load(), pairStarted[k].load()) << "pair " << k;
                if (k + 2 < strips) {
                    EXPECT_LT(pairDone[k + 1].load(), pairStarted[k].load()) << "pair " << k;
                }
            }
        }
    }
}

TEST(LevelTask, StripTouchesItsStrip_PairTouchesBoth) {
    EXPECT_FALSE(LevelTask::strip(3).isPair());
    EXPECT_EQ(LevelTask::strip(3).strips(), (StripRange{3, 3}));
    EXPECT_TRUE(LevelTask::pair(3).isPair());
    EXPECT_EQ(LevelTask::pair(3).strips(), (StripRange{3, 4}));
}

} // namespace
} // namespace terratin::detail
