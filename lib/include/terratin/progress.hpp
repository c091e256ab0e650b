#pragma once
/// @file
/// Progress reporting shared by every stage.

#include <functional>
#include <string_view>

namespace terratin {

/// Called with the fraction done (0..1) of the current stage and a short message. Returning
/// false asks the stage to stop: it then throws terratin::Cancelled.
using ProgressCallback = std::function<bool(double fraction, std::string_view message)>;

/// A callback for one part of a stage: maps the part's own 0..1 onto [start, start + share]
/// of `progress`. Empty when `progress` is.
inline ProgressCallback phaseProgress(const ProgressCallback& progress, double start,
                                      double share) {
    if (!progress)
        return {};
    return [progress, start, share](double fraction, std::string_view message) {
        return progress(start + share * fraction, message);
    };
}

} // namespace terratin
