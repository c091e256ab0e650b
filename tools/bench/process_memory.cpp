#include "process_memory.hpp"

#include <malloc.h>
#include <sys/mman.h>

#include <fstream>
#include <string>

namespace terratin::bench {

namespace {

// A "Key:   1234 kB" line of /proc/self/status, in bytes.
std::optional<std::size_t> statusBytes(const std::string& key) {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind(key + ":", 0) != 0)
            continue;
        try {
            constexpr std::size_t kBytesPerKiB = 1024;
            return std::stoull(line.substr(key.size() + 1)) * kBytesPerKiB;
        } catch (const std::exception&) {
            return std::nullopt;
        }
    }
    return std::nullopt;
}

bool resetPeakResidentSet() {
    std::ofstream clearRefs("/proc/self/clear_refs");
    clearRefs << "5";
    clearRefs.flush();
    return static_cast<bool>(clearRefs);
}

} // namespace

std::optional<std::size_t> residentBytes() {
    return statusBytes("VmRSS");
}

void PeakMemoryProbe::start() {
    // Memory freed by the previous run but kept by malloc would otherwise sit in the baseline
    // and be reused unseen by this one.
    malloc_trim(0);
    m_baselineBytes = resetPeakResidentSet() ? residentBytes() : std::nullopt;
}

void warmFreeMemory(std::size_t bytes) {
    if (bytes == 0)
        return;
    void* memory = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (memory == MAP_FAILED)
        return; // only a warm-up: the run will fault its pages in itself
    // The triangulators' large arrays are on huge pages: take the same kind of blocks.
    madvise(memory, bytes, MADV_HUGEPAGE);
    constexpr std::size_t kPageBytes = 4096;
    auto* const bytePointer = static_cast<volatile unsigned char*>(memory);
    for (std::size_t offset = 0; offset < bytes; offset += kPageBytes)
        bytePointer[offset] = 1;
    munmap(memory, bytes);
}

std::optional<std::size_t> PeakMemoryProbe::peakGrowthBytes() const {
    if (!m_baselineBytes)
        return std::nullopt;
    const std::optional<std::size_t> peak = statusBytes("VmHWM");
    if (!peak)
        return std::nullopt;
    return *peak > *m_baselineBytes ? *peak - *m_baselineBytes : 0;
}

} // namespace terratin::bench
