#pragma once
/// @file
/// What the refiner's exact check at positions (cellsToInsertAt, located_check.hpp) keeps of
/// each cell from one check to the next: the slot and version of the triangle that held it.
/// The next check then skips the cells whose triangle is unchanged and starts each walk near
/// the cell (CheckMemo). One owner for the five per-cell arrays, so that they stay in step;
/// they stay separate arrays because the check reads them as spans, cell after cell.

#include "located_check.hpp"
#include "refine_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

class CheckHistory {
public:
    /// No cell checked yet.
    explicit CheckHistory(std::size_t cellCount);

    /// The memo for the next check of `mesh`, whose extracted TIN has triangle k in slot
    /// slots[k]. Before any check it skips nothing; after one, it skips the cells whose
    /// triangle still has the slot and version recorded. Valid until the next call.
    [[nodiscard]] CheckMemo prepare(const RefineMesh& mesh, std::span<const TriId> slots);

    /// After the check prepare() was for: remembers, for each cell it checked, the slot and
    /// version of the triangle holding it strictly inside (none for a cell on an edge, which
    /// is checked again next time).
    void record(const RefineMesh& mesh, std::span<const TriId> slots);

private:
    /// Per cell, the triangle that held it at the last check: its slot (kNoTriangle: check
    /// the cell again) and that slot's version then.
    std::vector<TriId> m_slot;
    std::vector<std::uint32_t> m_version;
    /// The memo's arrays (CheckMemo): per cell, skip it; where its walk may start; where the
    /// check found it.
    std::vector<std::uint8_t> m_unchanged;
    std::vector<std::int32_t> m_near;
    std::vector<std::int32_t> m_located;
    bool m_checked = false;
};

} // namespace terratin::detail
