#pragma once
// How much of the machine's time its hypervisor gave to other guests (steal time), from
// Linux's /proc/stat: timings taken while it is high measure the neighbours, not the code.

#include <cstdint>
#include <optional>
#include <string_view>

namespace terratin::bench {

/// The all-CPU line of /proc/stat, in clock ticks.
struct CpuTimes {
    std::uint64_t total = 0; ///< user, nice, system, idle, iowait, irq, softirq and steal
    std::uint64_t steal = 0;
};

/// Reads the "cpu " line of /proc/stat's text; nothing when it is missing or malformed (a
/// kernel before 2.6.11 has no steal field).
[[nodiscard]] std::optional<CpuTimes> parseCpuTimes(std::string_view procStat);

/// The share of all CPU time stolen between start() and stolenShare(), 0 to 1; nothing where
/// /proc/stat cannot be read (another OS) or no tick went by.
class HostStealProbe {
public:
    void start();
    [[nodiscard]] std::optional<double> stolenShare() const;

private:
    std::optional<CpuTimes> m_start;
};

} // namespace terratin::bench
