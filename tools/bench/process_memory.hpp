#pragma once
// The resident memory a call adds at its peak, from Linux's /proc/self/status.

#include <cstddef>
#include <optional>

namespace terratin::bench {

/// Measures how far the process's peak resident set (VmHWM) rises above its resident set at
/// start(): the memory a call touches, temporaries and its result included.
///
/// start() hands freed heap memory back to the kernel (malloc_trim) and resets VmHWM (writing
/// 5 to /proc/self/clear_refs, Linux 4.0 and later), so that each measurement starts afresh.
/// Where either file cannot be used (another OS, a restricted container) the probe is
/// unavailable and peakGrowthBytes() returns nothing: the tables then say "n/a".
/// Resolution: one page (4 KiB); other threads' allocations during the call count too.
class PeakMemoryProbe {
public:
    /// Takes the baseline. Not to be timed: it costs a system call or three.
    void start();

    /// Bytes of peak resident memory above the baseline since start(), or nothing when the
    /// kernel does not let us measure it.
    [[nodiscard]] std::optional<std::size_t> peakGrowthBytes() const;

private:
    std::optional<std::size_t> m_baselineBytes;
};

/// The process's resident set now (VmRSS), or nothing where /proc/self/status is missing.
[[nodiscard]] std::optional<std::size_t> residentBytes();

/// Touches `bytes` of fresh memory, one write per page, and frees it again, so that a call
/// made right after gets pages the host backs. On a virtual machine that hands free memory
/// back to its hypervisor (virtio-balloon free page reporting), the first touch of such
/// memory is far slower than the next (figures in docs/benchmarks.md).
/// Which pages a timed run got then changed its time by up to a second between identical
/// runs, for every method and peer alike; this takes that cost out of the timer, leaving
/// the kernel's own page zeroing in it.
void warmFreeMemory(std::size_t bytes);

} // namespace terratin::bench
