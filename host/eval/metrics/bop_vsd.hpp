// BOP's Visible Surface Discrepancy (Hodan et al., ECCV 2018; bop_toolkit_lib/pose_error.py vsd
// with visibility.py's "bop19" masks), given the model rendered alone at the estimated and at
// the ground-truth pose (vsd_rendering.hpp) and the test depth image. Everything is compared as
// distances from the camera centre (depth_distance.hpp), as the toolkit does:
//   visib_gt  = gt rendered and (dist_gt - dist_test <= delta or no test depth)
//   visib_est = est rendered and (dist_est - dist_test <= delta or no test depth, or visib_gt)
//   error(tau) = (#{inter: |dist_gt - dist_est| / diameter >= tau} + #union - #inter) / #union
// (1 if the union is empty), the differences against delta in float32 as in the toolkit.
// VSD looks at visible surfaces only, so it needs no symmetries.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "synth/bop_visibility.hpp"
#include "synth/render/part_silhouette.hpp"

namespace binpick::eval {

// eval_bop19_pose.py: delta 15 mm for binpick's kind of data (the toolkit's per-dataset value,
// 5 for ITODD), tau = 0.05 .. 0.5 of the diameter, correct below 0.05 .. 0.5.
inline constexpr double kBopVsdDelta = 15.0;
std::vector<double> bop_vsd_taus();
std::vector<double> bop_vsd_thresholds();

struct VsdSettings {
  double delta_mm = kBopVsdDelta;
  std::vector<double> taus = bop_vsd_taus();
  bool normalized_by_diameter = true;  // taus are fractions of the diameter (else mm)
  double diameter = 1;                 // mm
};

// One error per tau. est and gt hold the model's depth (z, mm, > 0) on its pixels (row-major
// indices, increasing, as the renderer gives them). Throws InputError for a silhouette that is
// not sorted, leaves the image or has as many depths as pixels, or a depth image of the wrong
// size.
std::vector<double> vsd_errors(const PartSilhouette& est, const PartSilhouette& gt,
                               const BopDepthImage& test, const Eigen::Matrix3d& K,
                               const VsdSettings& settings);

// misc.overlapping_sphere_projections: do the images of two spheres of this radius centred at
// p1 and p2 (camera frame, mm) overlap (approximately)? eval_calc_errors.py gives VSD 1 for
// every tau without rendering when they do not; false if either centre has z = 0.
bool sphere_projections_overlap(double radius, const Eigen::Vector3d& p1,
                                const Eigen::Vector3d& p2);

}  // namespace binpick::eval
