#include "terratin/huge_pages.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace terratin {

void* allocateOnHugePages(std::size_t bytes) {
    if (bytes < kHugePageThreshold) {
        void* memory = std::malloc(bytes == 0 ? 1 : bytes);
        if (memory == nullptr)
            throw std::bad_alloc();
        return memory;
    }
    const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    void* memory = std::aligned_alloc(kHugePageBytes, rounded);
    if (memory == nullptr)
        throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // Only advice: without transparent huge pages the memory simply uses normal pages.
    madvise(memory, rounded, MADV_HUGEPAGE);
#endif
    return memory;
}

} // namespace terratin
