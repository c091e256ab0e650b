// Storage on huge pages: small and large blocks hold what is written, buffers move, arrays
// behave like vectors, and a worst-case capacity far beyond what is touched is only address
// space.

#include "huge_pages.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

namespace terratin::detail {
namespace {

TEST(HugePages, BuffersHoldWhatIsWritten_SmallAndLarge) {
    for (const std::size_t count :
         {std::size_t{10}, std::size_t{3} << 20U, (std::size_t{5} << 20U) + 7}) {
        HugePageBuffer<std::uint32_t> buffer(count);
        ASSERT_NE(buffer.data(), nullptr);
        for (std::size_t i = 0; i < count; ++i)
            buffer[i] = static_cast<std::uint32_t>(i * 2654435761U);
        HugePageBuffer<std::uint32_t> moved(std::move(buffer));
        EXPECT_EQ(buffer.data(), nullptr);
        EXPECT_EQ(moved.size(), count);
        for (std::size_t i = 0; i < count; i += 4093)
            ASSERT_EQ(moved[i], static_cast<std::uint32_t>(i * 2654435761U));
        EXPECT_EQ(moved[count - 1], static_cast<std::uint32_t>((count - 1) * 2654435761U));
        if (count * sizeof(std::uint32_t) >= kHugePageThreshold) { // aligned to a huge page
            EXPECT_EQ(reinterpret_cast<std::uintptr_t>(moved.data()) % kHugePageBytes, 0U);
        }
    }
}

TEST(HugePages, VectorsWithTheAllocatorBehaveLikeVectors) {
    std::vector<float, HugePageAllocator<float>> values(std::size_t{1} << 19U); // 2 MiB
    std::iota(values.begin(), values.end(), 0.0F);
    values.resize(values.size() * 3); // grows through a reallocation
    EXPECT_EQ(values[12345], 12345.0F);
    EXPECT_EQ(values.back(), 0.0F);
    std::vector<float, HugePageAllocator<float>> small(16, 1.5F); // below the threshold
    EXPECT_EQ(small[15], 1.5F);
}

TEST(HugePages, ArraysBehaveLikeVectors_AndLargeOnesStartOnAHugePage) {
    HugePageArray<std::uint64_t> values(std::size_t{3} << 18U, 7); // 6 MiB, every element 7
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(values.data()) % kHugePageBytes, 0U);
    EXPECT_EQ(values.front(), 7U);
    EXPECT_EQ(values.back(), 7U);
    std::iota(values.begin(), values.end(), std::uint64_t{0});
    values.push_back(42); // grows through a reallocation, keeping what was written
    EXPECT_EQ(values[123457], 123457U);
    EXPECT_EQ(values.back(), 42U);
    values.resize(10); // shrinking keeps the front
    EXPECT_EQ(values[9], 9U);
    HugePageArray<std::uint64_t>().swap(values); // the way the triangulator frees one early
    EXPECT_EQ(values.capacity(), 0U);
}

TEST(HugePages, ALargeCapacityIsOnlyAddressSpaceUntilTouched) {
#if defined(__linux__)
    std::ifstream overcommit("/proc/sys/vm/overcommit_memory");
    int mode = 0;
    overcommit >> mode;
    if (mode == 2)
        GTEST_SKIP() << "strict overcommit accounting";
    // Four times this machine's memory would be refused by the kernel's overcommit check
    // if it were reserved memory rather than address space.
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    std::size_t kilobytes = 0;
    meminfo >> key >> kilobytes;
    const std::size_t bytes = 4 * kilobytes * 1024;
    HugePageBuffer<char> buffer(bytes);
    buffer[0] = 'a';
    buffer[bytes - 1] = 'z';
    EXPECT_EQ(buffer[0], 'a');
    EXPECT_EQ(buffer[bytes - 1], 'z');
#else
    GTEST_SKIP() << "reserved address space is a Linux feature here";
#endif
}

} // namespace
} // namespace terratin::detail
