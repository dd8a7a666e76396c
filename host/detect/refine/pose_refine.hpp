// Refinement and verification of candidate poses against the measured depth (docs/pipeline.md,
// "Refinement and the verified score").
//
// Refinement: point-to-plane ICP with projective association. The model points visible at the
// current pose are paired with the measured point at their pixel; pairs farther apart along the
// ray than a gate are dropped, the rest weighted by Tukey's biweight of their point-to-plane
// residual, and one damped Gauss-Newton step solves for a small rotation about the posed
// centroid and a translation. The gate shrinks geometrically from a wide one (a pose one
// 12-degree alpha bin off moves the part's rim by about a fifth of its diameter) to twice the
// inlier tolerance over the iterations, so that the first steps pull a rough pose in and the
// last ones fit only the surface that agrees.
//
// Verification: at the refined pose, the score is
//     agreement / max(visible - missing / 2, min_support)
// visible = model points facing the camera and not hidden by the model itself, missing = those
// where the sensor has no depth (they count half: neither for the pose nor fully against it,
// since a pose parked over a shadow or beyond the sensor's range would otherwise be judged on a
// few points; measured, this halved the wrong top poses at 5 % noise), agreement = the sum over
// inliers (measured point within the tolerance of the model's tangent plane) of
// 1 - (distance / tolerance)^2, so that a closer fit scores higher. Model surface where the
// sensor sees through it or something lies in front of it counts against the pose. min_support
// (a fraction of the model's points) keeps a pose that shows the camera only a sliver (a plate
// edge on) from scoring high on a handful of points.
// With outline_ratio > 0 the score is then multiplied by the share of the pose's outline where
// the measured surface steps down rather than continuing at the part's depth (a pose laid on the
// wrong object, whose surface runs on past the model's edge, loses; docs/pipeline.md).
// With patches in the geometry (patch_bias.hpp), the score is also multiplied by the share of
// the model's patches whose residuals average out: a pose whose surface agrees on average but
// not in every region (a similar but different object) loses.
// With noise_factor > 0 the tolerance follows the sensor: the residuals of the best-fitting pose
// within a wide gate give the noise, and the tolerance becomes noise_factor times it, between
// the fixed tolerance and three times that (docs/parameters.md has the measurement).
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
  float tolerance_ratio = 0.04f;  // inlier tolerance, fraction of the diameter
  float min_support_ratio = 0.1f; // score's least denominator, fraction of the model's points
  std::uint32_t min_pairs = 12;   // fewer associated points: stop refining (the step is unsound)
  // > 0: the verification tolerance widens to this many times the sensor noise seen in the
  // best-fitting pose (at most 3 x the fixed one); 0: fixed.
  float noise_factor = 0.0f;
  // > 0: the outline test (pose_fit_shared.h) with this depth tolerance, fraction of the
  // diameter; the score is multiplied by the share of outline cells where the measured surface
  // steps down (1 - continue / (continue + step)). 0: off (thin parts: pose_refine.cpp).
  float outline_ratio = 0.0f;
  // > 0 (and the geometry's points and normals): the ray test (ray_spread.hpp). A pose whose
  // residuals along the viewing rays spread wider than the image's best pose's (the sensor's
  // noise) by more than this dead band (fraction of the diameter) has its score multiplied by
  // band / excess. 0: off.
  float ray_band_ratio = 0.0f;
  // > 0: the see-through cost. A visible model point where the sensor measured a surface
  // farther away, outside the tolerance, is free space where the pose puts the part: evidence
  // against the pose, not only no evidence for it. The score is multiplied by
  // max(0, 1 - through_weight * see_through / support) (support: visible minus half the
  // missing, as in the score). 0: off (such points only fail to agree).
  float through_weight = 0.0f;
  // > 0 (and the geometry's points, normals and mean area): the seen-area test
  // (seen_area.hpp). The score is multiplied by min(1, seen area / (area_scale x mean area)).
  // 0: off.
  float area_scale = 0.0f;
  // Keep each pose's measured points (RefinedPose::measured) for the rival test
  // (rival.hpp); depth images only, whose measured points lie on the pixels' rays.
  bool keep_measured = false;
  // Depth images: the near gate (pose_fit_shared.h, bp_near_gate) in the last ICP steps and the
  // verification passes, from the image's depth noise (mm, depth_noise.hpp). A plate partly
  // covered by another was pulled 1.9 degrees off by it and lost to its own flip
  // (docs/pipeline.md, step 8).
  bool near_gate = false;
  float noise = 0;
};
void check(const RefineOptions& opt);

struct RefinedPose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double score = 0;            // in [0, 1]
  std::uint32_t visible = 0, missing = 0, inliers = 0, see_through = 0, occluded = 0;
  std::uint32_t outline_continue = 0, outline_step = 0;  // outline cells (0 without the test)
  std::uint32_t patches_tested = 0, patches_biased = 0;  // the patch test (0 without it)
  bool ray_tested = false;       // the ray test ran on this pose
  double ray_excess = 0;        // mm, its excess RMS along the rays (0 without it)
  bool twin_tested = false;      // the twin test ran on this pose (lookalike_holes.hpp)
  double twin_excess = 0;        // mm, its largest depth excess at a look-alike's probes
  bool edge_tested = false;      // the edge test ran on this pose (edge_step.hpp)
  double edge_step = 0;          // mm, the step down at its edges (an upper bound)
  bool area_tested = false;      // the seen-area test ran on this pose (seen_area.hpp)
  double area_share = 0;         // its seen area over the part's mean area
  // The rival test (rival.hpp): out-fitted by another pose on shared measured points, its
  // mean clipped squared residual there (mm^2) against the rival's.
  bool rival_out_fitted = false;
  std::uint32_t rival_shared = 0;
  double own_ms = 0, rival_ms = 0;
  // The best score of its look-alikes (lookalike_share.hpp), before their shares; 0 if none.
  double lookalike_score = 0;
  double fit_score = 0;  // the score before the look-alike share (the same without one)
  // The measured points of its ICP terms at the final pose (RefineOptions::keep_measured).
  std::vector<Eigen::Vector3f> measured;
  std::uint32_t iterations = 0;  // ICP steps taken
  float tolerance = 0;           // mm, the verification tolerance used (the same for all poses)
  std::string reason;          // why the score is 0 or refinement stopped early; empty if neither
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
// (each pose is its own work group; the tolerance that follows the noise is worked out after
// the iterations), so what the memo holds stands: the longest prefix of the poses equal bit for
// bit to the inputs it holds keeps their refined poses, and only the rest are iterated.
struct RefineMemo {
  std::vector<PoseToRefine> inputs, refined;
  std::vector<std::uint32_t> iterations;
  std::vector<std::string> reasons;  // why refinement stopped early; empty if it did not
};

// Refines all poses together (one kernel launch per iteration for all of them) and scores them.
// geometry.diameter, voxel_size > 0; model_points = the model's point count (for min_support).
// With a memo (one image, the same options every call), the poses it holds are not iterated
// again, and it then holds all of these: the same results as without it.
std::vector<RefinedPose> refine_and_verify(const FitSumsFn& sums, const bp_camera& cam,
                                           const FitGeometry& geometry,
                                           std::uint32_t model_points,
                                           const std::vector<PoseToRefine>& poses,
                                           const RefineOptions& opt = {},
                                           RefineMemo* memo = nullptr);

// One damped Gauss-Newton step from the sums: (rotation vector about the pose's centre,
// translation), zero when the system is empty.
Eigen::Matrix<double, 6, 1> gauss_newton_step(const FitSums& sums);

}  // namespace binpick
