// After-the-fact check of a dropped bin: is it really at rest? Rebuilds the pile from the
// poses, lets every part move under gravity for a while with nothing frozen, and measures how
// far each one went. A pile that was frozen while still tipping or sagging moves; a settled
// one stays put (up to contact jitter).
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "host/core/mesh.hpp"
#include "synth/decompose/convex_parts.hpp"
#include "synth/physics/drop.hpp"

namespace binpick {

struct SettleDrift {
  int parts = 0;
  int moved_over_1mm = 0;  // of their centres of mass
  int moved_over_5mm = 0;
  double worst_mm = 0.0;       // largest move of a centre of mass
  double worst_degrees = 0.0;  // largest turn
  std::vector<double> moved_mm;  // per pose, in order
};

// `poses` (part -> world, mm) as drop_parts returned them for `options`; `seconds` simulated.
SettleDrift settle_drift(const ConvexParts& hulls, const Mesh& part, const DropOptions& options,
                         const std::vector<Eigen::Isometry3d>& poses, double seconds = 1.0);

}  // namespace binpick
