#pragma once
/// @file
/// Not API: the allocators of the library's big public arrays (MeshArray in
/// triangulate/tin_mesh.hpp, HeightArray in geometry/height_grid.hpp), here only because those
/// arrays' types need them whole. Name the arrays by those aliases, never these allocators:
/// they may change without notice. Why huge pages: lib/src/huge_pages.hpp.

#include <cstddef>
#include <new>
#include <utility>

namespace terratin::detail {

/// `bytes` of uninitialised storage, on 2 MiB pages when it is large (lib/src/huge_pages.hpp);
/// release it with releaseHugePages(memory, bytes). Throws std::bad_alloc.
void* allocateOnHugePages(std::size_t bytes);
void releaseHugePages(void* memory, std::size_t bytes) noexcept;

/// A std::allocator that puts allocations of a megabyte or more on huge pages.
template <class T> struct HugePageAllocator {
    using value_type = T;

    HugePageAllocator() = default;
    template <class U> explicit HugePageAllocator(const HugePageAllocator<U>& /*other*/) noexcept {}

    [[nodiscard]] T* allocate(std::size_t n) {
        return static_cast<T*>(allocateOnHugePages(n * sizeof(T)));
    }
    void deallocate(T* p, std::size_t n) noexcept { releaseHugePages(p, n * sizeof(T)); }
    friend bool operator==(const HugePageAllocator& /*a*/, const HugePageAllocator& /*b*/) {
        return true;
    }
};

/// A HugePageAllocator whose resize() leaves new elements default-initialised (unwritten, for
/// trivial types) where std::allocator value-initialises. The big arrays of a triangulation
/// are sized and then filled on all threads: zeros written first by resize() would be a pass
/// over tens of megabytes on one thread.
template <class T> struct HugePageArrayAllocator : HugePageAllocator<T> {
    template <class U> struct rebind { using other = HugePageArrayAllocator<U>; };
    HugePageArrayAllocator() = default;
    template <class U>
    explicit HugePageArrayAllocator(const HugePageArrayAllocator<U>& /*other*/) noexcept {}

    template <class U> void construct(U* p) noexcept { ::new (static_cast<void*>(p)) U; }
    template <class U, class... Args> void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

} // namespace terratin::detail
