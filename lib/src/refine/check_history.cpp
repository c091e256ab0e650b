#include "check_history.hpp"

#include <algorithm>

namespace terratin::detail {

CheckHistory::CheckHistory(std::size_t cellCount)
    : m_slot(cellCount, kNoTriangle), m_version(cellCount, 0), m_located(cellCount, -1) {}

CheckMemo CheckHistory::prepare(const RefineMesh& mesh, std::span<const TriId> slots) {
    const std::size_t cellCount = m_slot.size();
    if (m_checked) {
        std::vector<std::int32_t> indexOfSlot(mesh.slotEnd(), -1);
        for (std::size_t k = 0; k < slots.size(); ++k)
            indexOfSlot[slots[k]] = static_cast<std::int32_t>(k);
        m_unchanged.resize(cellCount);
        m_near.resize(cellCount);
        for (std::size_t cell = 0; cell < cellCount; ++cell) {
            const TriId slot = m_slot[cell];
            const bool known = slot != kNoTriangle && slot < indexOfSlot.size();
            m_unchanged[cell] = known && mesh.version(slot) == m_version[cell] ? 1 : 0;
            m_near[cell] = known ? indexOfSlot[slot] : -1;
        }
    }
    std::fill(m_located.begin(), m_located.end(), -1);
    return {m_unchanged, m_near, m_located};
}

void CheckHistory::record(const RefineMesh& mesh, std::span<const TriId> slots) {
    for (std::size_t cell = 0; cell < m_slot.size(); ++cell) {
        if (!m_unchanged.empty() && m_unchanged[cell] != 0)
            continue;
        m_slot[cell] =
            m_located[cell] >= 0 ? slots[static_cast<std::size_t>(m_located[cell])] : kNoTriangle;
        if (m_slot[cell] != kNoTriangle)
            m_version[cell] = mesh.version(m_slot[cell]);
    }
    m_checked = true;
}

} // namespace terratin::detail
