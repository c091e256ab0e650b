#include "repair_rendezvous.hpp"

#include <algorithm>

namespace terratin::detail {

void RepairRendezvous::request(NodeId firstNode) {
    const std::lock_guard lock(m_mutex);
    m_firstNode = std::min(m_firstNode, firstNode);
    m_requested.store(true, std::memory_order_release);
}

void RepairRendezvous::arrive() {
    std::unique_lock lock(m_mutex);
    if (!m_requested.load(std::memory_order_relaxed) || m_stopped)
        return;
    ++m_arrivedWorkers;
    const std::size_t repairsBefore = m_repairs;
    repairIfAllArrived();
    m_repaired.wait(lock, [&] { return m_repairs != repairsBefore || m_stopped; });
}

void RepairRendezvous::leave() {
    const std::lock_guard lock(m_mutex);
    --m_workingWorkers;
    if (m_requested.load(std::memory_order_relaxed) && !m_stopped)
        repairIfAllArrived();
}

void RepairRendezvous::stop() {
    {
        const std::lock_guard lock(m_mutex);
        m_stopped = true;
    }
    m_repaired.notify_all();
}

void RepairRendezvous::repairIfAllArrived() {
    if (m_arrivedWorkers < m_workingWorkers)
        return;
    // Everyone else waits for the mutex-guarded count of repairs, so the flips run alone.
    m_flips += m_triangulator.repairEdgesFrom(m_firstNode);
    ++m_repairs;
    m_firstNode = kNoNode;
    m_arrivedWorkers = 0;
    m_requested.store(false, std::memory_order_release);
    m_repaired.notify_all();
}

} // namespace terratin::detail
