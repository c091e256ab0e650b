#include "progress_printer.hpp"

#include <algorithm>

namespace terratin::cli {

namespace {
// GDAL prints a number every 10 % and a dot every 2.5 % in between.
constexpr int kTicks = 40;
} // namespace

bool ProgressPrinter::update(double fraction) {
    const int target = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * kTicks);
    while (m_ticks < target) {
        ++m_ticks;
        if (m_ticks % 4 == 0)
            std::fprintf(m_stream, "%d", m_ticks / 4 * 10);
        else
            std::fputc('.', m_stream);
    }
    if (m_ticks == kTicks)
        endLine(" - done.");
    std::fflush(m_stream);
    return !m_cancelRequested->load();
}

void ProgressPrinter::finish() {
    if (lineUnderWay())
        update(1.0);
}

void ProgressPrinter::fail() {
    if (lineUnderWay())
        endLine(" - failed.");
    std::fflush(m_stream);
}

void ProgressPrinter::printLine(std::string_view text) {
    if (lineUnderWay()) {
        m_pending.emplace_back(text);
        return;
    }
    std::fprintf(m_stream, "%.*s\n", static_cast<int>(text.size()), text.data());
    std::fflush(m_stream);
}

bool ProgressPrinter::lineUnderWay() const {
    return m_ticks >= 0 && m_ticks <= kTicks;
}

void ProgressPrinter::endLine(std::string_view ending) {
    std::fprintf(m_stream, "%.*s\n", static_cast<int>(ending.size()), ending.data());
    m_ticks = kTicks + 1; // the line is complete: print nothing more
    for (const auto& line : m_pending)
        std::fprintf(m_stream, "%s\n", line.c_str());
    m_pending.clear();
}

} // namespace terratin::cli
