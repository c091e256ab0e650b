#pragma once
/// @file
/// SIGTERM and SIGHUP during a library call from Python: by default they end the process at
/// once, leaving the call's temporary files behind (the command line cleans up on the same
/// signals). While a TerminationSignals lives, a signal whose handler is the default one only
/// sets a flag that cancels the call; the call cleans up, and then the signal is raised again
/// with its default action, so the process still ends as the sender asked. A handler the
/// program installed itself (signal.signal) is left alone.

#include "terratin/progress.hpp"

#include <csignal>

namespace terratin::python {

class TerminationSignals {
public:
    /// Takes over SIGTERM and SIGHUP where their handler is the default.
    TerminationSignals();
    TerminationSignals(const TerminationSignals&) = delete;
    TerminationSignals& operator=(const TerminationSignals&) = delete;
    /// Puts the handlers back as they were.
    ~TerminationSignals();

    /// `progress`, returning false from the first call after a signal came.
    [[nodiscard]] ProgressCallback cancelling(ProgressCallback progress) const;

    /// When a signal came: restores its default action and raises it (the process ends).
    void reraiseIfReceived() const;

private:
    struct Taken {
        int signal = 0;
        bool taken = false;
        struct sigaction previous {};
    };
    Taken m_taken[2];
};

} // namespace terratin::python
