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
///
/// The allocators and allocateOnHugePages / releaseHugePages are declared in
/// terratin/detail/huge_page_allocator.hpp, since the public arrays (MeshArray, HeightArray)
/// need them; the rest is the library's own.

#include "terratin/detail/huge_page_allocator.hpp"

#include <cstddef>
#include <utility>
#include <vector>

namespace terratin::detail {

/// Bytes of a huge page, and the smallest allocation worth aligning to one.
/// allocateOnHugePages puts a block of at least kHugePageThreshold bytes on huge pages, as
/// reserved address space (MAP_NORESERVE on Linux): only pages touched take memory, so a
/// capacity sized for the worst case costs nothing until used, and the kernel's overcommit
/// check does not refuse it. Smaller blocks come from malloc.
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20U;
inline constexpr std::size_t kHugePageThreshold = std::size_t{1} << 20U;

/// An owned array of `count` T on huge pages (allocateOnHugePages), elements uninitialised:
/// for implicit-lifetime types the caller writes before reading.
template <class T> class HugePageBuffer {
public:
    HugePageBuffer() = default;
    explicit HugePageBuffer(std::size_t count)
        : m_data(static_cast<T*>(allocateOnHugePages(count * sizeof(T)))), m_count(count) {}
    ~HugePageBuffer() { release(); }
    HugePageBuffer(const HugePageBuffer&) = delete;
    HugePageBuffer& operator=(const HugePageBuffer&) = delete;
    HugePageBuffer(HugePageBuffer&& other) noexcept
        : m_data(std::exchange(other.m_data, nullptr)), m_count(std::exchange(other.m_count, 0)) {}
    HugePageBuffer& operator=(HugePageBuffer&& other) noexcept {
        if (this != &other) {
            release();
            m_data = std::exchange(other.m_data, nullptr);
            m_count = std::exchange(other.m_count, 0);
        }
        return *this;
    }

    [[nodiscard]] T* data() const { return m_data; }
    [[nodiscard]] std::size_t size() const { return m_count; }
    [[nodiscard]] T& operator[](std::size_t i) const { return m_data[i]; }

private:
    void release() {
        if (m_data != nullptr)
            releaseHugePages(m_data, m_count * sizeof(T));
        m_data = nullptr;
    }
    T* m_data = nullptr;
    std::size_t m_count = 0;
};

/// A vector on huge pages whose resize() leaves new elements unwritten: for the arrays of
/// megabytes that a triangulation makes and fills once. Besides the TLB (above), huge pages
/// are taken by the kernel at one fault per 2 MiB where normal pages cost one per 4 KiB: a
/// fresh array of tens of megabytes is ready several times sooner. The same type as the public
/// MeshArray (tin_mesh.hpp).
template <class T> using HugePageArray = std::vector<T, HugePageArrayAllocator<T>>;

} // namespace terratin::detail
