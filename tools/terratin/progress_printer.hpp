#pragma once
// Renders progress the way GDAL's command-line tools do: "0...10...20...30...40...50...60...
// 70...80...90...100 - done." on stderr.

#include "terratin/progress.hpp"

#include <atomic>
#include <cstdio>
#include <string_view>

namespace terratin::cli {

/// A ProgressCallback that prints GDAL-style ticks to `stream` and stops the run (returns
/// false) once `cancelRequested` becomes true.
class ProgressPrinter {
public:
    ProgressPrinter(std::FILE* stream, const std::atomic<bool>& cancelRequested)
        : m_stream(stream), m_cancelRequested(&cancelRequested) {}

    /// Prints the ticks up to `fraction`; returns false when cancellation was requested.
    bool update(double fraction);

    /// Completes the line ("100 - done.") if it was started.
    void finish();

    /// Ends a half-printed line so that an error message starts on a line of its own.
    void breakLine();

    /// Prints `text` as a line of its own (a notice) and, when a progress line was under way,
    /// starts it again on the next line with the ticks already printed.
    void printLine(std::string_view text);

    ProgressCallback callback() {
        return [this](double fraction, std::string_view) { return update(fraction); };
    }

private:
    std::FILE* m_stream;
    const std::atomic<bool>* m_cancelRequested;
    /// Ticks printed so far: 0..40, one per 2.5 %.
    int m_ticks = -1;
};

} // namespace terratin::cli
