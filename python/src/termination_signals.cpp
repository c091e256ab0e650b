#include "termination_signals.hpp"

#include <atomic>
#include <utility>

namespace terratin::python {

namespace {

/// The signal that came, 0 for none; written by the handler, which may only touch a lock-free
/// atomic.
std::atomic<int> g_received{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void onTermination(int signal) {
    g_received.store(signal);
}

} // namespace

TerminationSignals::TerminationSignals() {
    g_received.store(0);
    const int signals[] = {SIGTERM, SIGHUP};
    for (int i = 0; i < 2; ++i) {
        Taken& taken = m_taken[i];
        taken.signal = signals[i];
        if (sigaction(taken.signal, nullptr, &taken.previous) != 0 ||
            taken.previous.sa_handler != SIG_DFL)
            continue;
        struct sigaction action {};
        action.sa_handler = onTermination;
        sigemptyset(&action.sa_mask);
        taken.taken = sigaction(taken.signal, &action, nullptr) == 0;
    }
}

TerminationSignals::~TerminationSignals() {
    for (const Taken& taken : m_taken)
        if (taken.taken)
            sigaction(taken.signal, &taken.previous, nullptr);
}

ProgressCallback TerminationSignals::cancelling(ProgressCallback progress) const {
    return [progress = std::move(progress)](double fraction, std::string_view message) {
        if (g_received.load() != 0)
            return false;
        return progress ? progress(fraction, message) : true;
    };
}

void TerminationSignals::reraiseIfReceived() const {
    const int signal = g_received.load();
    if (signal == 0)
        return;
    struct sigaction defaultAction {};
    defaultAction.sa_handler = SIG_DFL;
    sigemptyset(&defaultAction.sa_mask);
    sigaction(signal, &defaultAction, nullptr);
    std::raise(signal);
}

} // namespace terratin::python
