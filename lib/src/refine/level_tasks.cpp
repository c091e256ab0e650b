#include "level_tasks.hpp"

#include <algorithm>
#include <numeric>

namespace terratin::detail {

LevelPlan planLevel(std::span<const std::size_t> stripCandidates) {
    const std::size_t n = stripCandidates.size();
    std::vector<std::uint8_t> order(n);
    std::iota(order.begin(), order.end(), std::uint8_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::uint8_t a, std::uint8_t b) {
        return stripCandidates[a] > stripCandidates[b];
    });
    LevelPlan plan;
    std::vector<std::size_t> stripTask(n);
    for (const std::uint8_t k : order) {
        stripTask[k] = plan.graph.add();
        plan.tasks.push_back(LevelTask::strip(k));
    }
    std::vector<std::size_t> pairTask(n > 0 ? n - 1 : 0);
    for (const std::uint8_t parity : {std::uint8_t{0}, std::uint8_t{1}})
        for (std::uint8_t k = parity; k + 1U < n; k += 2) {
            pairTask[k] = plan.graph.add();
            plan.tasks.push_back(LevelTask::pair(k));
            plan.graph.after(pairTask[k], stripTask[k]);
            plan.graph.after(pairTask[k], stripTask[k + 1]);
            if (parity == 1) {
                plan.graph.after(pairTask[k], pairTask[k - 1]);
                if (k + 2U < n)
                    plan.graph.after(pairTask[k], pairTask[k + 1]);
            }
        }
    return plan;
}

} // namespace terratin::detail
