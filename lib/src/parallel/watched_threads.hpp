#pragma once
/// @file
/// Worker threads watched by the calling thread, which does no share of their work: it calls
/// a watch function every kWatchInterval until they have all returned. The parallel methods
/// pass a watch that calls the progress callback, so that a cancel (the callback returning
/// false, Ctrl-C in the CLI) is seen within that interval however long the workers insert or
/// wait for one another, and however many of them share few cores. The calling thread is not
/// one of the workers because a worker reports only between its own steps, and can be stuck in
/// a wait, or descheduled among thousands of spinning threads, for minutes.
/// The callback is still called from the calling thread only.

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace terratin::detail {

/// How often the calling thread calls its watch while workers run. A cancel is seen within
/// this plus the time the workers take to notice their stop flag (every loop of theirs, the
/// waits included, tests it). Short against a person's patience; long against one progress
/// callback (microseconds), so the watching costs nothing measurable.
inline constexpr std::chrono::milliseconds kWatchInterval{20};

/// Runs body(index) for every index of [0, count), each on a thread of its own, while the
/// calling thread calls watch() every kWatchInterval until every body has returned (the last
/// one to return wakes it: no interval is waited out). When watch() returns false or throws,
/// stop() is called once and watch() no more; the bodies must then return soon (they test a
/// flag that stop() sets). Returns false when the watch asked to stop. Rethrows the first
/// exception of a body, else the watch's, after every thread has returned.
/// Precondition: count >= 1.
template <class Body, class Watch, class Stop>
bool runWatched(unsigned count, Body&& body, Watch&& watch, Stop&& stop) {
    std::mutex mutex;
    std::condition_variable finished;
    unsigned running = count;
    std::exception_ptr failure;
    std::exception_ptr watchFailure;
    bool keepGoing = true;
    const auto run = [&](unsigned index) {
        try {
            body(index);
        } catch (...) {
            const std::lock_guard lock(mutex);
            if (!failure)
                failure = std::current_exception();
        }
        // Notified under the lock: the waiting thread cannot return (and destroy the
        // condition variable) between the count reaching 0 and the notification.
        const std::lock_guard lock(mutex);
        if (--running == 0)
            finished.notify_all();
    };
    {
        std::vector<std::jthread> threads;
        threads.reserve(count);
        try {
            for (unsigned index = 0; index < count; ++index)
                threads.emplace_back(run, index);
        } catch (...) {
            // No thread for the rest: the started ones are told to stop, and counted down.
            stop();
            const std::lock_guard lock(mutex);
            running -= count - static_cast<unsigned>(threads.size());
            if (!failure)
                failure = std::current_exception();
        }
        std::unique_lock lock(mutex);
        while (!finished.wait_for(lock, kWatchInterval, [&] { return running == 0; })) {
            if (!keepGoing)
                continue;
            lock.unlock();
            try {
                keepGoing = watch();
            } catch (...) {
                watchFailure = std::current_exception();
                keepGoing = false;
            }
            if (!keepGoing)
                stop();
            lock.lock();
        }
    }
    if (failure)
        std::rethrow_exception(failure);
    if (watchFailure)
        std::rethrow_exception(watchFailure);
    return keepGoing;
}

} // namespace terratin::detail
