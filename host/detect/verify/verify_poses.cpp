#include "host/detect/verify/verify_poses.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/detect/verify/patch_bias.hpp"
#include "host/detect/verify/ray_spread.hpp"
#include "host/detect/verify/rival.hpp"
#include "host/detect/verify/seen_area.hpp"

namespace binpick {
namespace {

// Phase 1: the tolerance follows the sensor's noise, as the best-fitting pose shows it (its
// residual's weighted RMS within a wide gate of 4 tolerances), so that a noisy image's right
// poses are not judged by a tolerance inside its noise. It widens to at most three times the
// fixed one, never narrows (docs/detect/verify.md, "The tolerance";
// docs/decisions/2026-11-24-tolerance-follows-noise.md). Returns the tolerance and the final
// pass's gate.
std::pair<float, float> image_tolerance(const std::vector<FitSums>& wide, float tolerance,
                                        float gate_end, const VerifyOptions& opt) {
  double noise = INFINITY;
  for (const FitSums& s : wide) {
    // The Tukey weights' sum is the trace of the translation block (unit normals).
    const double weight = s.jtj(3, 3) + s.jtj(4, 4) + s.jtj(5, 5);
    if (s.used >= opt.refine.min_pairs && weight > 0)
      noise = std::min(noise, std::sqrt(s.cost / weight));
  }
  const float widened = std::isfinite(noise)
                            ? std::clamp(float(opt.noise_factor * noise), tolerance, 3 * tolerance)
                            : tolerance;
  if (widened > 1.05f * tolerance) return {widened, 2 * widened};
  return {tolerance, gate_end};
}

}  // namespace

void check(const VerifyOptions& o) {
  check(o.refine);
  const auto bad = [](double v, double lo, double hi) { return !(v >= lo && v <= hi); };
  if (bad(o.noise_factor, 0, 100))
    throw InputError(fmt::format("verify noise factor {} must be in [0, 100]", o.noise_factor));
  if (bad(o.outline_ratio, 0, 1))
    throw InputError(fmt::format("outline tolerance {} must be in [0, 1]", o.outline_ratio));
  if (bad(o.through_weight, 0, 100))
    throw InputError(fmt::format("see-through weight {} must be in [0, 100]", o.through_weight));
  if (bad(o.area_scale, 0, 10))
    throw InputError(fmt::format("seen-area scale {} must be in [0, 10]", o.area_scale));
  if (bad(o.ray_band_ratio, 0, 1))
    throw InputError(fmt::format("ray spread band {} must be in [0, 1]", o.ray_band_ratio));
  if (bad(o.min_support_ratio, 0, 1))
    throw InputError(fmt::format("verify min support {} must be in [0, 1]", o.min_support_ratio));
}

std::vector<VerifiedPose> verify_poses(const FitSumsFn& sums_of, const bp_camera& cam,
                                       const FitGeometry& g, std::uint32_t model_points,
                                       const std::vector<RefinedPose>& poses,
                                       const VerifyOptions& opt) {
  check(opt);
  const RefineOptions& ro = opt.refine;
  std::vector<bp_pose_fit> fits;
  const auto pass = [&](float tol, float gate, float outline, bool residuals) {
    FitThresholds th = fit_thresholds(g, tol, gate, ro);
    th.outline = outline;
    th.residuals = residuals;
    fits.clear();
    for (const RefinedPose& p : poses) fits.push_back(make_pose_fit(p.R, p.t, cam, g, th));
    return sums_of(fits);
  };
  float tolerance = ro.tolerance_ratio * g.diameter;
  float final_gate = std::min(ro.gate_start_ratio * g.diameter, 2.0f * tolerance);
  if (opt.noise_factor > 0)
    std::tie(tolerance, final_gate) =
        image_tolerance(pass(tolerance, 4 * tolerance, 0.0f, false), tolerance, final_gate, opt);

  // The patch bias's dead band: a quarter of the fixed tolerance (0.01 d by default), the size
  // of a right pose's leftover error; it does not widen with the noise (its significance does).
  PatchBiasOptions patch_opt;
  patch_opt.dead_band = 0.25f * ro.tolerance_ratio * g.diameter;
  const bool patch_on = g.patches.count > 0;
  const bool geometry = g.points.size() == model_points && g.normals.size() == model_points;
  const bool ray_on = opt.ray_band_ratio > 0 && !g.points.empty() && geometry;
  const bool area_on = opt.area_scale > 0 && g.mean_area > 0 && geometry;
  const bool keep_measured = opt.keep_measured && geometry;
  const std::vector<FitSums> sums = pass(tolerance, final_gate, opt.outline_ratio * g.diameter,
                                         patch_on || ray_on || keep_measured || area_on);
  const double min_support = double(opt.min_support_ratio) * model_points;
  // Phase 1 too: the image's noise along the rays is the least spread among its poses.
  std::vector<RaySpread> ray(poses.size());
  RaySpread ray_noise;
  if (ray_on) {
    for (std::size_t k = 0; k < poses.size(); ++k)
      if (sums[k].residuals.size() == model_points)
        ray[k] = ray_spread(
            ray_residuals(sums[k].residuals, poses[k].R, poses[k].t, g.points, g.normals));
    ray_noise = ray_floor(ray);
  }

  std::vector<VerifiedPose> out(poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    VerifiedPose& v = out[k];
    const FitSums& s = sums[k];
    PoseEvidence& e = v.evidence;
    ScoreBreakdown& b = v.breakdown;
    v.R = poses[k].R;
    v.t = poses[k].t;
    v.iterations = poses[k].iterations;
    v.reason = poses[k].reason;
    e.visible = s.visible();
    e.missing = s.count[BP_FIT_MISSING];
    e.inliers = s.count[BP_FIT_INLIER];
    e.see_through = s.count[BP_FIT_SEE_THROUGH];
    e.occluded = s.count[BP_FIT_OCCLUDED];
    e.tolerance = tolerance;
    e.outline_continue = s.outline_continue;
    e.outline_step = s.outline_step;
    if (keep_measured && s.residuals.size() == model_points)
      v.measured = measured_points(s.residuals, v.R, v.t, g.points, g.normals, cam);
    if (e.visible == 0) {
      v.reason = "no model surface visible at this pose";
      continue;
    }
    if (e.visible == e.missing) {
      v.reason = "no depth where the model would be seen";
      continue;
    }
    // Phase 2, in the score's order.
    b[kAgreement] = agreement_factor(s.agreement, e.visible, e.missing, min_support);
    b[kSeeThrough] = see_through_factor(opt.through_weight, e.see_through,
                                        score_support(e.visible, e.missing, min_support));
    b[kOutline] = outline_factor(s.outline_step, s.outline_continue);
    if (patch_on) {
      const PatchBias pb = patch_bias(s.residuals, g.patches, patch_opt);
      e.patches_tested = pb.tested;
      e.patches_biased = pb.biased;
      b[kPatchBias] = pb.factor();
    }
    if (area_on && s.classes.size() == model_points) {
      e.area_tested = true;
      e.area_share = seen_area(s.classes, v.R, v.t, g.points, g.normals) / g.mean_area;
      b[kSeenArea] = area_factor(e.area_share, opt.area_scale);
    }
    // Fewer residuals than refinement needs: too few to tell a spread from the noise.
    if (ray_on && ray_noise.n > 0 && ray[k].n >= ro.min_pairs) {
      e.ray_tested = true;
      e.ray_excess = ray_excess(ray[k], ray_noise);
      b[kRaySpread] = excess_factor(e.ray_excess, double(opt.ray_band_ratio) * g.diameter);
    }
  }
  return out;
}

std::vector<VerifiedPose> refine_and_verify(const FitSumsFn& sums, const bp_camera& cam,
                                            const FitGeometry& geometry,
                                            std::uint32_t model_points,
                                            const std::vector<PoseToRefine>& poses,
                                            const VerifyOptions& opt, RefineMemo* memo) {
  return verify_poses(sums, cam, geometry, model_points,
                      refine_poses(sums, cam, geometry, poses, opt.refine, memo), opt);
}

}  // namespace binpick
