#include "cancel_signals.hpp"

#include <signal.h>

#include <string>

namespace terratin::cli {

namespace {

std::atomic<bool> g_cancelRequested{false};
std::atomic<int> g_firstSignal{0};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

extern "C" void requestCancel(int signal) {
    int none = 0;
    g_firstSignal.compare_exchange_strong(none, signal);
    g_cancelRequested.store(true);
}

void ignore(int signal) {
    struct sigaction action {};
    action.sa_handler = SIG_IGN;
    sigemptyset(&action.sa_mask);
    sigaction(signal, &action, nullptr);
}

} // namespace

void installCancelSignals() {
    struct sigaction cancel {};
    cancel.sa_handler = requestCancel;
    sigemptyset(&cancel.sa_mask);
    cancel.sa_flags = SA_RESTART;
    // SIGHUP (the terminal was closed) like Ctrl-C and kill: no hidden temporary is left
    // behind.
    for (const int signal : {SIGINT, SIGTERM, SIGHUP})
        sigaction(signal, &cancel, nullptr);
    // Past `ulimit -f` the write fails with EFBIG instead of the run dying without a word;
    // a closed stdout or stderr pipe fails its write with EPIPE instead of
    // killing the run in the middle of writing its output.
    ignore(SIGXFSZ);
    ignore(SIGPIPE);
}

const std::atomic<bool>& cancelledBySignal() {
    return g_cancelRequested;
}

std::string cancellingSignalName() {
    switch (g_firstSignal.load()) {
    case SIGINT:
        return "SIGINT";
    case SIGTERM:
        return "SIGTERM";
    case SIGHUP:
        return "SIGHUP";
    default:
        return {};
    }
}

} // namespace terratin::cli
