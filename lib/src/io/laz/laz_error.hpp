#pragma once
/// @file
/// The one way the LAZ decoder reports a file it cannot decode: an InvalidInputError whose
/// single line names the stage, the file and what is wrong with it.

#include "terratin/error.hpp"

#include <string>
#include <string_view>

namespace terratin::io::laz {

inline constexpr std::string_view kLazStage = "LazReader";

[[noreturn]] inline void throwInvalidLaz(std::string_view fileName, const std::string& what) {
    throw InvalidInputError(std::string(kLazStage) + ": '" + std::string(fileName) + "': " + what);
}

} // namespace terratin::io::laz
