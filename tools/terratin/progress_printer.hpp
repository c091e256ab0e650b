#pragma once
// Renders progress the way GDAL's command-line tools do: "0...10...20...30...40...50...60...
// 70...80...90...100 - done." on stderr.

#include "terratin/progress.hpp"

#include <atomic>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

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

    /// Ends a half-printed line with " - failed." so that the error message that follows is
    /// stderr's last line, whole, and no bare fragment ("0...10") is left before it.
    void fail();

    /// Prints `text` as a line of its own (a notice); while a progress line is under way it
    /// waits for the line's end, so that no fragment ("0...") is ever left on a line of its own.
    void printLine(std::string_view text);

    ProgressCallback callback() {
        return [this](double fraction, std::string_view) { return update(fraction); };
    }

private:
    /// True between the first tick and the line's end.
    [[nodiscard]] bool lineUnderWay() const;
    /// Ends the progress line with `ending`, then prints the lines that waited for it.
    void endLine(std::string_view ending);

    std::FILE* m_stream;
    const std::atomic<bool>* m_cancelRequested;
    /// Ticks printed so far: 0..40, one per 2.5 %.
    int m_ticks = -1;
    /// Lines printLine received while the progress line was under way.
    std::vector<std::string> m_pending;
};

} // namespace terratin::cli
