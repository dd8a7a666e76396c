// "Up" for the bin fit (bin_fit.hpp) when no plane gives it: the direction along which the
// rim, the highest structure at one height along the image's border, holds the most samples.
// In a bin full of bulky parts the floor is buried and the pile offers no level plane, so none
// of the planes found (bin_planes.hpp) is level, and seen from a tilted camera the optical axis
// is not either; but the rim runs along the border at one height only along the true up, where
// its samples gather in one height bin. Host code on the sparse sample (a few ten thousand
// points), coarse to fine over the directions facing the camera.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "host/detect/bin/bin_planes.hpp"
#include "host/detect/bin/bin_rim.hpp"

namespace binpick {

struct RimUpSearch {
  double tol = 5.0;            // height tolerance, mm (the plane search's)
  double band = 0.25;          // the border band: this fraction of the image on each side
  double max_tilt_deg = 40.0;  // directions up to this far from the optical axis
};

struct RimUp {
  Eigen::Vector3d up = Eigen::Vector3d(0, 0, -1);  // unit, facing the camera
  std::size_t support = 0;                         // rim_support at it, at width tol
};

// How well up levels the rim: fit_rim's first step, heights up . p in bins of `width` summed
// over three bins; from the top, the first local maximum that holds at least 3 % of the biggest
// sum, 1 % of the band and 20 samples, and of whose samples at least max(5, 5 %) lie along each
// of three sides. Its sum less twice the samples above it (0 if that is negative, or if there is
// no such peak): the rim is the highest thing along the border, and a direction that makes some
// other structure one "height" (a wall's face, the ground and a side of the rim) tips samples
// over it.
std::size_t rim_support(const BorderBand& band, const Eigen::Vector3d& up, double width);

// The direction facing the camera (within max_tilt_deg of the optical axis) with the greatest
// rim_support: a grid of 2-degree steps on 2000 of the band's samples, then 0.5 degree about the
// four best on 6000, then 0.125 degree about the two best of those on 12000. The coarser steps
// count heights in bins as wide as a direction half a step off spreads the band's samples, so
// that the rim is not missed between grid points. Not beyond 40 degrees by default: a wall's
// inner face seen from a camera tilted 30 degrees faces it at 60 and would be one "height"
// along the border too. Nothing if no direction has a rim
// (docs/decisions/2026-11-25-bin-up-searched-along-rim.md).
std::optional<RimUp> search_rim_up(const PlaneSamples& samples, const RimUpSearch& opt);

}  // namespace binpick
