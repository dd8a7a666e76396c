// Refinement of candidate poses against the measured depth: point-to-plane ICP with projective
// association (docs/detect/refine.md). Verification, which scores the refined poses, is
// verify/verify_poses.hpp.
//
// The model points visible at the current pose are paired with the measured point at their
// pixel; pairs farther apart along the ray than a gate are dropped, the rest weighted by Tukey's
// biweight of their point-to-plane residual, and one damped Gauss-Newton step solves for a small
// rotation about the posed centroid and a translation. The gate shrinks geometrically from a
// wide one (a pose one 12-degree alpha bin off moves the part's rim by about a fifth of its
// diameter) to twice the inlier tolerance over the iterations, so that the first steps pull a
// rough pose in and the last ones fit only the surface that agrees.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/detect/refine/pose_fit.hpp"

namespace binpick {

struct RefineOptions {
  std::uint32_t iterations = 10;  // ICP steps; 0: verify only
  float gate_start_ratio = 0.2f;  // first association gate, fraction of the diameter
  float tolerance_ratio = 0.04f;  // inlier tolerance, fraction of the diameter (the last gate is 2x)
  std::uint32_t min_pairs = 12;   // fewer associated points: stop refining (the step is unsound)
  // Depth images: the near gate (pose_fit_shared.h, bp_near_gate) in the last ICP steps and the
  // verification passes, from the image's depth noise (mm, depth_noise.hpp): what lies on the
  // part is kept out of its fit.
  bool near_gate = false;
  float noise = 0;
};
void check(const RefineOptions& opt);

// A candidate pose after ICP.
struct RefinedPose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  std::uint32_t iterations = 0;  // ICP steps taken
  std::string reason;            // why refinement stopped early; empty if it did not
};

// The sums of the given fits against one scene: pose_fit_sums on a device scene, or the
// reference (tests).
using FitSumsFn = std::function<std::vector<FitSums>(const std::vector<bp_pose_fit>&)>;

struct PoseToRefine {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

// The ICP of poses refined before against the same image with the same options: an image's
// second round of hypotheses refines the first round's candidates again together with its own
// (detector.cpp, in_rounds). A pose's ICP depends only on the pose, the image and the options
// (each pose is its own work group; verification's tolerance that follows the noise is worked
// out after the iterations), so what the memo holds stands: the longest prefix of the poses equal bit for
// bit to the inputs it holds keeps their refined poses, and only the rest are iterated.
struct RefineMemo {
  std::vector<PoseToRefine> inputs, refined;
  std::vector<std::uint32_t> iterations;
  std::vector<std::string> reasons;  // why refinement stopped early; empty if it did not
};

// Refines all poses together (one kernel launch per iteration for all of them).
// geometry.diameter > 0. With a memo (one image, the same options every call), the poses it holds
// are not iterated again, and it then holds all of these: the same results as without it.
std::vector<RefinedPose> refine_poses(const FitSumsFn& sums, const bp_camera& cam,
                                      const FitGeometry& geometry,
                                      const std::vector<PoseToRefine>& poses,
                                      const RefineOptions& opt = {}, RefineMemo* memo = nullptr);

// The thresholds of a fit at a gate and tolerance (mm), with the near gate where opt asks.
FitThresholds fit_thresholds(const FitGeometry& geometry, float tolerance, float gate,
                             const RefineOptions& opt);

// One damped Gauss-Newton step from the sums: (rotation vector about the pose's centre,
// translation), zero when the system is empty.
Eigen::Matrix<double, 6, 1> gauss_newton_step(const FitSums& sums);

}  // namespace binpick
