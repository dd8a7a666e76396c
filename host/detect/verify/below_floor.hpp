// A physical check of a pose against the bin found in the image: a part cannot lie below the
// bin's floor. Verification alone cannot tell: a pose that sinks a part into the floor shows
// the camera only the faces that coincide with the floor (a shaft's top, a bracket's face), and
// those agree with the measured floor as well as a real part's faces agree with the part.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "host/core/mesh.hpp"
#include "host/detect/verify/verified_pose.hpp"

namespace binpick {

// A pose with more than this fraction of its model points below the floor scores 0.
inline constexpr double kMaxBelowFloor = 0.1;

// The fraction of the model's points that the pose (model -> camera) puts farther than margin
// (mm) below the plane up . p + d = 0 (up: the floor's normal toward the camera, unit). 0 for an
// empty model.
double fraction_below_floor(const PointCloud& model, const Eigen::Matrix3d& R,
                            const Eigen::Vector3d& t, const Eigen::Vector3d& up, double d,
                            double margin);

// Sets the below-floor factor (score.hpp) of every pose with a positive score that puts more
// than kMaxBelowFloor of the model's points below the floor by more than the larger of its
// verification tolerance and a tenth of the diameter (a right pose's error or a thin part's, and
// the floor fit's, stay inside it), with the reason.
void mark_below_floor(std::vector<VerifiedPose>& poses, const PointCloud& model, double diameter,
                      const Eigen::Vector3d& up, double d);

}  // namespace binpick
