// Radians per degree, for the files that state their thresholds in degrees.
#pragma once

#include <numbers>

namespace binpick {

inline constexpr double kDeg = std::numbers::pi / 180;

}  // namespace binpick
