// A bin found anywhere in view (--bin W,D,H, and --bin auto where the border gives none), not
// only where its rim runs along the image's border: in a real cell the bin may fill a third of the view, turned,
// in front of clutter (docs/detect/bin.md, "Anywhere in view"). The rim is a rectangular strip
// at one height whose inner edges are W and D apart: at each candidate up, each height slice
// and each turn, the strips show as pairs of peaks that far apart (any span, without a size) in
// the slice's histograms across the two axes; the best pairs are then refined and judged by how much of the rectangle's
// perimeter the strip covers. Host code on the bin fit's sparse samples.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/detect/bin/bin_planes.hpp"

namespace binpick {

struct RimSearch {
  // The interior W >= D (mm); zero: any size between min_side and max_side each way (--bin auto).
  Eigen::Vector2d size = Eigen::Vector2d::Zero();
  double min_side = 100, max_side = 3000;
  double tol = 5;             // the fit's height tolerance (mm): slices are 2 tol thick
  double strip = 60;          // the widest rim strip outside the inner edge (wall, lip; mm)
  double cell = 10;           // histogram bin (mm)
  double turn_step_deg = 2;   // turns tried, then refined from the strips
  double min_coverage = 0.5;  // share of the perimeter's segments the strip must reach
  double min_side_coverage = 0.6;  // without a size: of each side's segments
  double min_contrast = 4;    // the strip this many times denser than the bands beside it
  double max_above = 0.2;     // share of the samples inside that may stand above the rim
  std::size_t min_slice = 40; // samples a slice needs to be searched
};

struct AnywhereRim {
  bool found = false;
  std::string why;
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d a1 = Eigen::Vector3d::UnitX();  // along W
  Eigen::Vector3d a2 = Eigen::Vector3d::UnitY();  // along D, up x a1
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // the interior's centre along a1, a2 (mm)
  Eigen::Vector2d size = Eigen::Vector2d::Zero();    // its W along a1, D along a2 (mm)
  // Samples inside it more than 3 tol above its lowest ones: what it holds (an empty tray: 0).
  std::size_t held = 0;
  double height = 0;     // up . p of the rim's top
  double coverage = 0;   // share of the perimeter's segments reached
  std::size_t points = 0;  // samples on the strip
};

// The best rectangle over the candidate ups (unit, toward the camera): of a given size, the one
// whose strip reaches most of its perimeter; of any size, of those that pass, the one holding
// most (a bin with parts before an empty tray). Never throws for a scene without one: found =
// false and why.
AnywhereRim find_rim_anywhere(const PlaneSamples& s, const std::vector<Eigen::Vector3d>& ups,
                        const RimSearch& opt);

}  // namespace binpick
