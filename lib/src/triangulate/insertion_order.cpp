#include "insertion_order.hpp"

#include <utility>

namespace terratin::detail {

namespace {

// splitmix64 (Steele, Lea & Flood 2014): tiny state, passes BigCrush, fully portable.
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : m_state(seed) {}
    std::uint64_t operator()() {
        std::uint64_t z = (m_state += 0x9E3779B97F4A7C15ULL);
        z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31U);
    }

private:
    std::uint64_t m_state;
};

// Uniform integer in [0, bound) without modulo bias (Lemire 2019, "Fast random integer
// generation in an interval").
std::uint32_t boundedRandom(SplitMix64& random, std::uint32_t bound) {
    auto product = (random() >> 32U) * std::uint64_t{bound};
    auto low = static_cast<std::uint32_t>(product);
    if (low < bound) {
        const std::uint32_t threshold = (0U - bound) % bound;
        while (low < threshold) {
            product = (random() >> 32U) * std::uint64_t{bound};
            low = static_cast<std::uint32_t>(product);
        }
    }
    return static_cast<std::uint32_t>(product >> 32U);
}

} // namespace

std::vector<std::uint32_t> randomInsertionOrder(std::uint32_t count, std::uint32_t skip,
                                                std::uint64_t seed) {
    std::vector<std::uint32_t> order;
    order.reserve(count);
    for (std::uint32_t v = 0; v < count; ++v)
        if (v != skip)
            order.push_back(v);
    SplitMix64 random(seed);
    for (std::size_t i = order.size(); i > 1; --i) {
        const std::uint32_t j = boundedRandom(random, static_cast<std::uint32_t>(i));
        std::swap(order[i - 1], order[j]);
    }
    return order;
}

} // namespace terratin::detail
