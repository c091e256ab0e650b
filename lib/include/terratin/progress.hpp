#pragma once
/// @file
/// Progress reporting shared by every stage.

#include <functional>
#include <string_view>

namespace terratin {

/// Called with the fraction done (0..1) of the current stage and a short message. Returning
/// false asks the stage to stop: it then throws terratin::Cancelled.
using ProgressCallback = std::function<bool(double fraction, std::string_view message)>;

} // namespace terratin
