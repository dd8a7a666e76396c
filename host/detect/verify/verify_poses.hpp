// Verification of refined poses against the measured depth: the score's image context and its
// per-pose factors from one last pass of the pose fit (docs/detect/verify.md, "The score";
// score.hpp has the model). The factors that need more than one pass or more than one pose
// (look-alike holes, edge step, below floor, rival, look-alike share) are applied after it by
// verify_candidates (verify_candidates.hpp), in the score's order.
#pragma once

#include <cstdint>
#include <vector>

#include "host/detect/refine/pose_fit.hpp"
#include "host/detect/refine/pose_refine.hpp"
#include "host/detect/verify/verified_pose.hpp"

namespace binpick {

struct VerifyOptions {
  // Refinement (refine/pose_refine.hpp); its tolerance, minimum of pairs, near gate and noise
  // are verification's too.
  RefineOptions refine;
  float min_support_ratio = 0.1f;  // agreement's least denominator, fraction of the model's points
  // > 0: the tolerance widens to this many times the sensor noise seen in the best-fitting pose
  // (at most 3 x the fixed one, never narrower); 0: fixed.
  float noise_factor = 0.0f;
  // > 0: the outline factor with this depth tolerance (fraction of the diameter); 0: off (thin
  // parts: outline.hpp).
  float outline_ratio = 0.0f;
  // > 0 (and the geometry's points and normals): the ray spread factor's dead band (fraction of
  // the diameter; ray_spread.hpp). 0: off.
  float ray_band_ratio = 0.0f;
  // > 0: the see-through factor's weight (score.hpp, see_through_factor). 0: off.
  float through_weight = 0.0f;
  // > 0 (and the geometry's points, normals and mean area): the seen-area factor's scale
  // (seen_area.hpp). 0: off.
  float area_scale = 0.0f;
  // Keep each pose's measured points (VerifiedPose::measured) for the rival (rival.hpp);
  // depth images only, whose measured points lie on the pixels' rays.
  bool keep_measured = false;
};
void check(const VerifyOptions& opt);

// Phase 1 (the tolerance, the ray spread's noise floor) and phase 2's factors from the fit pass
// (agreement, see-through, outline, patch bias, seen area, ray spread) of every pose.
// model_points: the fit model's point count (the minimum support's unit).
std::vector<VerifiedPose> verify_poses(const FitSumsFn& sums, const bp_camera& cam,
                                       const FitGeometry& geometry, std::uint32_t model_points,
                                       const std::vector<RefinedPose>& poses,
                                       const VerifyOptions& opt = {});

// refine_poses, then verify_poses.
std::vector<VerifiedPose> refine_and_verify(const FitSumsFn& sums, const bp_camera& cam,
                                            const FitGeometry& geometry,
                                            std::uint32_t model_points,
                                            const std::vector<PoseToRefine>& poses,
                                            const VerifyOptions& opt = {},
                                            RefineMemo* memo = nullptr);

}  // namespace binpick
