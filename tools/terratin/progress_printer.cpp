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
        std::fputs(" - done.\n", m_stream);
    std::fflush(m_stream);
    if (m_ticks == kTicks)
        m_ticks = kTicks + 1; // the line is complete: print nothing more
    return !m_cancelRequested->load();
}

void ProgressPrinter::finish() {
    if (m_ticks >= 0 && m_ticks <= kTicks)
        update(1.0);
}

void ProgressPrinter::breakLine() {
    if (m_ticks >= 0 && m_ticks <= kTicks) {
        std::fputc('\n', m_stream);
        m_ticks = kTicks + 1;
    }
}

} // namespace terratin::cli

namespace terratin::cli {

void ProgressPrinter::printLine(std::string_view text) {
    const bool midLine = m_ticks >= 0 && m_ticks < kTicks;
    if (midLine)
        std::fputc('\n', m_stream);
    std::fprintf(m_stream, "%.*s\n", static_cast<int>(text.size()), text.data());
    if (midLine) {
        // Start the progress line again with the ticks already printed.
        const int printed = m_ticks;
        m_ticks = -1;
        update(static_cast<double>(printed) / kTicks);
    }
    std::fflush(m_stream);
}

} // namespace terratin::cli
