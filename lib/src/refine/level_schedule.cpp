#include "level_schedule.hpp"

#include <algorithm>

namespace terratin::detail {

double levelBelow(double top, double threshold, double firstPriority, std::size_t strips) {
    if (strips == 1)
        return threshold; // one strip: plain greedy insertion, no levels needed
    if (top == kHolePriority)
        return std::numeric_limits<double>::max(); // the holes' candidates first, alone
    const double level = top * kLevelRatio;
    return level > threshold && level > firstPriority * kNegligibleErrorFraction ? level
                                                                                 : threshold;
}

bool finishesExactly(std::size_t left, std::size_t strips) {
    return left < kMinStripQuota * strips;
}

std::size_t taskQuota(std::size_t left, std::size_t strips) {
    return left == kNoQuota ? left : left / (2 * strips);
}

std::size_t pointsUnderLimits(std::optional<std::size_t> maxPoints,
                              std::optional<std::size_t> maxTriangles, std::size_t points,
                              std::size_t triangles) {
    std::size_t left = kNoQuota;
    if (maxPoints)
        left = *maxPoints - std::min(*maxPoints, points);
    if (maxTriangles)
        left = std::min(left, (*maxTriangles - std::min(*maxTriangles, triangles)) / 2);
    return left;
}

} // namespace terratin::detail
