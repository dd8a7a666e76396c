// The bin's floor for the bin fit (bin_fit.hpp): the level plane under the rim's frame that has
// nothing under it. Host code on the sparse sample the planes were found on.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "host/detect/bin/bin_planes.hpp"

namespace binpick {

struct FloorUnder {
  std::vector<double> heights;  // up . p of the samples inside the frame, lowest first
  std::optional<double> plane;  // the floor plane's height, if there is one
};

// The floor under the frame {a1 low, a1 high, a2 low, a2 high} (edges may be infinite: sides not
// seen): the level plane (within 5 degrees of up) with the most inliers inside (at least 50),
// more than 3 tol below the rim, that has nothing under it. A level layer of parts is no floor:
// in a full bin the most supported level plane inside is a layer of flat parts some centimetres
// up, and parts seen below it through the gaps would be "below the floor" (below_floor.hpp) and
// masked out (docs/decisions/2026-11-25-bin-floor-nothing-under.md). "Under" is beyond the depth
// noise: at most max(20, 0.2 %) of the samples inside lie more than max(3 tol, 4 noise) below it
// (at 3 % noise a floor's own samples reach 3 tol below it; a layer's gaps show parts and floor
// centimetres below). noise: the image's depth noise, sigma in mm (depth_noise.hpp).
FloorUnder floor_under(const PlaneSamples& samples, const std::vector<FoundPlane>& planes,
                       const Eigen::Vector3d& up, const Eigen::Vector3d& a1,
                       const Eigen::Vector3d& a2, const std::array<double, 4>& edge,
                       double rim_height, double tol, double noise);

}  // namespace binpick
