#include "huge_pages.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include <cstdint>
#include <cstdlib>
#include <new>

namespace terratin::detail {

namespace {

std::size_t roundedToHugePages(std::size_t bytes) {
    return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
}

} // namespace

void* allocateOnHugePages(std::size_t bytes) {
    if (bytes < kHugePageThreshold) {
        void* memory = std::malloc(bytes == 0 ? 1 : bytes);
        if (memory == nullptr)
            throw std::bad_alloc();
        return memory;
    }
    const std::size_t rounded = roundedToHugePages(bytes);
#if defined(__linux__)
    // Map a huge page more than needed and trim both ends to a huge-page boundary.
    void* mapped = mmap(nullptr, rounded + kHugePageBytes, PROT_READ | PROT_WRITE,
                        MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (mapped == MAP_FAILED)
        throw std::bad_alloc();
    const auto start = reinterpret_cast<std::uintptr_t>(mapped);
    const std::uintptr_t aligned = (start + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    if (aligned > start)
        munmap(mapped, aligned - start);
    const std::uintptr_t end = start + rounded + kHugePageBytes;
    if (end > aligned + rounded)
        munmap(reinterpret_cast<void*>(aligned + rounded), end - (aligned + rounded));
    void* memory = reinterpret_cast<void*>(aligned);
#if defined(MADV_HUGEPAGE)
    // Only advice: without transparent huge pages the memory simply uses normal pages.
    madvise(memory, rounded, MADV_HUGEPAGE);
#endif
    return memory;
#else
    void* memory = std::aligned_alloc(kHugePageBytes, rounded);
    if (memory == nullptr)
        throw std::bad_alloc();
    return memory;
#endif
}

void releaseHugePages(void* memory, std::size_t bytes) noexcept {
    if (memory == nullptr)
        return;
    if (bytes < kHugePageThreshold) {
        std::free(memory);
        return;
    }
#if defined(__linux__)
    munmap(memory, roundedToHugePages(bytes));
#else
    std::free(memory);
#endif
}

} // namespace terratin::detail
