// A side of the bin that the border band and the plane search miss (bin_fit.hpp). The rim is
// looked for along the image's border (bin_rim.hpp) and a side out of view ends at a wall plane
// found by RANSAC (bin_planes.hpp); failing both, the interior ran to the farthest point seen
// below the rim, which in wire-mesh baskets seen tilted took in too much: the wall's top beyond
// a side the band held too few samples of, or, through a far mesh wall that is no RANSAC plane,
// the ground beyond (docs/decisions/2026-11-29-bin-side-search.md).
// So two searches among all samples beyond the edge known, each a histogram along the axis in
// windows of two bins as wide as the rim fit's, whose nearest window that stands out (3 times
// the median window, empty ones included: a bin filled to the brim is a level sheet, not a
// side) and runs across most of the frame (6 of 10 cells of its width) ends the interior at
// its inner edge (the 10th percentile of its samples: parts lying against it share the window):
// - rim_strip_beyond: the samples at the rim's height (within 1.5 tolerances, as the rim's own);
// - wall_beyond: the samples below the rim (by more than 3 tolerances) spanning most of the
//   heights down to the lowest seen (4 of 10 cells): a wall's bars stand from the floor up;
//   the ground seen through a mesh beyond it lies at one level.
// Only for a frame with a level floor under it: a slice through a heap with no bin (the paper's
// scenes, where such a "frame" is found and then refused or kept as harmless) has contours and
// flanks that pass for sides.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "host/detect/bin/bin_planes.hpp"

namespace binpick {

struct SideSearch {
  Eigen::Vector3d up = Eigen::Vector3d(0, 0, -1);      // unit, toward the camera
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();     // unit, level: the side lies across it
  Eigen::Vector3d across = Eigen::Vector3d::UnitY();   // unit, level: the side runs along it
  double dir = 1;                 // +1: look toward +axis from `from`; -1: toward -axis
  double from = 0;                // axis . p of the edge known (or the frame's middle)
  double across_lo = 0, across_hi = 0;  // the frame's extent along `across` (mm)
  double rim_height = 0;          // up . p of the rim's top
  double tol = 5;                 // the fit's tolerance (mm)
};

// The distance from `from` along dir * axis to the inner edge of the nearest rim strip beyond it
// (more than 4 tolerances away), or nothing.
std::optional<double> rim_strip_beyond(const PlaneSamples& samples, const SideSearch& q);

// The same for the nearest wall beyond it: its inner face.
std::optional<double> wall_beyond(const PlaneSamples& samples, const SideSearch& q);

}  // namespace binpick
