// After-the-fact check of a dropped bin: how deep do any two parts overlap? Uses Bullet's own
// contact query on the hulls (no collision margins), independent of the simulation's world.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "synth/decompose/convex_parts.hpp"

namespace binpick {

// The largest penetration depth between any two parts at `poses` (part -> world, mm), 0 if
// none touch.
double deepest_penetration_mm(const ConvexParts& hulls,
                              const std::vector<Eigen::Isometry3d>& poses);

}  // namespace binpick
