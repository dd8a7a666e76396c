// What a part's symmetries are, in one line for people (`binpick train`, `binpick synth`).
#pragma once

#include <string>

#include "host/core/symmetry.hpp"

namespace binpick {

// "none found"; "continuous about (0, 0, 1) through (0, 0, -1.25)", with ", ends swapped by a
// half turn" when a discrete symmetry reverses the axis; "any rotation (a sphere)" for two
// axes; "5 discrete: 6-fold about (0, 0, 1)", the discrete ones grouped by their rotation axes
// (up to sign, within 1 degree) and each axis' order, the highest first, axes of one order in
// descending (x, y, z). Directions are shown with their largest component positive,
// coordinates rounded to 1e-4 (directions) and 1e-3 mm (points).
std::string describe_symmetries(const PartSymmetries& symmetries);

}  // namespace binpick
