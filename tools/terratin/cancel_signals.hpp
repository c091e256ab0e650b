#pragma once
// The signals a terratin run answers, and how: the ones that mean "stop" cancel the run at its
// next progress report, so that the writer removes its temporaries; the ones that would kill
// it half-way through writing are turned into ordinary write errors.

#include <atomic>
#include <string>

namespace terratin::cli {

/// Installs the handlers (once, before the run): SIGINT, SIGTERM and SIGHUP set the flag that
/// cancelledBySignal() returns; SIGXFSZ (a file-size limit) and SIGPIPE (a closed pipe) are
/// ignored, so the write fails with EFBIG or EPIPE and the normal error path cleans up.
void installCancelSignals();

/// True once one of the cancelling signals has arrived. Async-signal-safe to set, lock-free
/// to read.
const std::atomic<bool>& cancelledBySignal();

/// The first cancelling signal that arrived, for messages: "SIGINT", "SIGTERM" or "SIGHUP";
/// empty while none has.
std::string cancellingSignalName();

} // namespace terratin::cli
