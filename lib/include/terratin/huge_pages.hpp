#pragma once
/// @file
/// Large arrays on transparent huge pages.
///
/// The triangulator and the refiner read their big arrays (elevations, cell flags, points,
/// triangles) at random places. With 4 KiB pages nearly every such read misses the TLB as
/// well as the cache: a raster row is one page or more, so the cells of a triangle's rows lie
/// on as many pages. 2 MiB pages cut those page walks to almost nothing. Linux gives them to
/// memory advised with MADV_HUGEPAGE when transparent huge pages are in "madvise" mode (the
/// common default); elsewhere the advice is ignored and normal pages are used.

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>

namespace terratin {

/// Bytes of a huge page, and the smallest allocation worth aligning to one.
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20U;
inline constexpr std::size_t kHugePageThreshold = std::size_t{1} << 20U;

/// `bytes` of storage, huge-page aligned and advised when at least kHugePageThreshold
/// (rounded up to whole huge pages); release with std::free. Throws std::bad_alloc.
void* allocateOnHugePages(std::size_t bytes);

/// A std::allocator that puts allocations of kHugePageThreshold bytes or more on huge pages.
template <class T>
struct HugePageAllocator {
    using value_type = T;

    HugePageAllocator() = default;
    template <class U>
    explicit HugePageAllocator(const HugePageAllocator<U>& /*other*/) noexcept {}

    [[nodiscard]] T* allocate(std::size_t n) {
        if (n * sizeof(T) < kHugePageThreshold)
            return std::allocator<T>{}.allocate(n);
        return static_cast<T*>(allocateOnHugePages(n * sizeof(T)));
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) < kHugePageThreshold)
            std::allocator<T>{}.deallocate(p, n);
        else
            std::free(p);
    }
    friend bool operator==(const HugePageAllocator& /*a*/, const HugePageAllocator& /*b*/) {
        return true;
    }
};

} // namespace terratin
