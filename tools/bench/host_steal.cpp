#include "host_steal.hpp"

#include <array>
#include <charconv>
#include <fstream>
#include <string>
#include <system_error>

namespace terratin::bench {

namespace {

std::optional<CpuTimes> readCpuTimes() {
    std::ifstream file("/proc/stat");
    if (!file)
        return std::nullopt;
    std::string line;
    std::getline(file, line);
    return parseCpuTimes(line);
}

} // namespace

std::optional<CpuTimes> parseCpuTimes(std::string_view procStat) {
    constexpr std::string_view kPrefix = "cpu ";
    if (procStat.substr(0, kPrefix.size()) != kPrefix)
        return std::nullopt;
    // user nice system idle iowait irq softirq steal (guest time is counted in user already).
    std::array<std::uint64_t, 8> fields{};
    const char* at = procStat.data() + kPrefix.size();
    const char* const end = procStat.data() + procStat.size();
    for (std::uint64_t& field : fields) {
        while (at != end && *at == ' ')
            ++at;
        const auto [next, error] = std::from_chars(at, end, field);
        if (error != std::errc() || next == at)
            return std::nullopt;
        at = next;
    }
    CpuTimes times;
    for (const std::uint64_t field : fields)
        times.total += field;
    times.steal = fields[7];
    return times;
}

void HostStealProbe::start() {
    m_start = readCpuTimes();
}

std::optional<double> HostStealProbe::stolenShare() const {
    const std::optional<CpuTimes> now = readCpuTimes();
    if (!m_start || !now || now->total <= m_start->total)
        return std::nullopt;
    return static_cast<double>(now->steal - m_start->steal) /
           static_cast<double>(now->total - m_start->total);
}

} // namespace terratin::bench
