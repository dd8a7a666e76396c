// BOP's pose errors MSSD and MSPD (Hodan et al., BOP Challenge 2019; bop_toolkit_lib/pose_error.py)
// with BOP's symmetry transformations (misc.get_symmetry_transformations): the error of an
// estimate is the smallest, over the symmetric copies of the ground truth, of the largest
// distance of a model vertex between the estimate and the copy (3D for MSSD, in the image for
// MSPD). Continuous symmetries are discretised as the toolkit does, so the numbers match its.
#pragma once

#include <limits>
#include <vector>

#include <Eigen/Core>

#include "host/core/symmetry.hpp"

namespace binpick::eval {

// x -> R x + t in the model frame.
struct SymmetryTransform {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

// BOP's max_sym_disc_step (eval_bop19_pose.py): the vertex farthest from a continuous axis
// travels at most this fraction of the diameter between consecutive discretised rotations.
inline constexpr double kBopMaxSymmetryStep = 0.01;

// The toolkit's set: the identity and each discrete symmetry D; with continuous symmetries, each
// of them combined with every rotation C_i by i * 2 pi / n about each continuous axis (through
// its offset), i = 0..n-1, n = ceil(pi / max_step) (315 for 0.01), as C_i * D. The axes are not
// composed with each other (the toolkit lists each axis' rotations one after the other).
std::vector<SymmetryTransform> bop_symmetry_transforms(const PartSymmetries& symmetries,
                                                      double max_step = kBopMaxSymmetryStep);

struct RigidPose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();  // mm
};

// Maximum Symmetry-aware Surface Distance, mm: min over S of max over vertices v of
// |R_e v + t_e - (R_g (R_S v + t_S) + t_g)|. Needs at least one vertex and one transform.
// An error of `bound` or more is returned as some value >= bound without measuring it exactly
// (matching needs only errors below its largest threshold; far-off instances then cost about
// one vertex per transform).
double mssd(const RigidPose& estimate, const RigidPose& truth,
            const std::vector<Eigen::Vector3d>& vertices,
            const std::vector<SymmetryTransform>& symmetries,
            double bound = std::numeric_limits<double>::infinity());

// Maximum Symmetry-aware Projection Distance, pixels: as mssd with the points projected by K
// (x = K p / p_z, as misc.project_pts: no check that p_z > 0); `bound` as for mssd.
double mspd(const RigidPose& estimate, const RigidPose& truth, const Eigen::Matrix3d& K,
            const std::vector<Eigen::Vector3d>& vertices,
            const std::vector<SymmetryTransform>& symmetries,
            double bound = std::numeric_limits<double>::infinity());

}  // namespace binpick::eval
