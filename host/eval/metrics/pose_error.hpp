// Pose errors of the paper (section III-D): translation error = distance between the estimated
// and the ground-truth translation; rotation error = angle of the angle-axis of R_gt^T R_est,
// in [0, 180] degrees. For a symmetric part every symmetric copy of the ground truth is an
// equally right answer: the error is taken against the copy nearest in rotation.
#pragma once

#include <Eigen/Core>

#include "host/core/symmetry.hpp"

namespace binpick::eval {

// Angle of the rotation A^T B in degrees, in [0, 180]; robust near 0 and 180 degrees.
double rotation_angle_deg(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B);

struct PoseError {
  double translation_mm = 0;
  double rotation_deg = 0;
};

// Error of the estimate (R_est, t_est) against the ground truth (R_gt, t_gt) of a part with the
// given symmetries (model frame, BOP convention). The ground truth's symmetric copies are
// T_gt * D * C(theta) for D the identity or one of the discrete transforms and C(theta) the
// rotation by theta about the continuous axis (through its offset point); the copy with the
// smallest rotation error is chosen in closed form, and the translation error is taken against
// that same copy (an axis through the model origin leaves t as is). Two or more non-parallel
// continuous axes make every rotation symmetric (a sphere): the rotation error is then 0.
PoseError symmetric_pose_error(const Eigen::Matrix3d& R_gt, const Eigen::Vector3d& t_gt,
                               const Eigen::Matrix3d& R_est, const Eigen::Vector3d& t_est,
                               const PartSymmetries& symmetries);

// The angle theta (radians) minimising the angle of C(theta)^T M, with C(theta) the rotation
// about the unit axis: trace(C(-theta) M) = a^T M a + cos(theta) (tr M - a^T M a)
// - sin(theta) tr([a]x M) is largest there. Exposed for its test.
double best_angle_about_axis(const Eigen::Matrix3d& M, const Eigen::Vector3d& axis);

}  // namespace binpick::eval
