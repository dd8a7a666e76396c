#include "host/detect/refine/pose_refine.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/detect/verify/seen_area.hpp"
#include "host/detect/verify/ray_spread.hpp"
#include "host/detect/verify/rival.hpp"

namespace binpick {
namespace {

// A step rotates by at most this (radians): a step is a linearisation, trusted only nearby.
constexpr double kMaxStepAngle = 0.25;

FitThresholds thresholds(const FitGeometry& g, float tolerance, float gate,
                         const RefineOptions& opt) {
  FitThresholds th;
  th.gate = gate;
  th.tolerance = tolerance;
  th.slack = zbuffer_slack(g, th.tolerance);
  if (opt.near_gate) th.near_gate = bp_near_gate(gate, tolerance, opt.noise);
  return th;
}

void apply_step(const Eigen::Matrix<double, 6, 1>& x, const Eigen::Vector3d& centre,
                PoseToRefine& pose) {
  Eigen::Vector3d w = x.head<3>();
  if (w.norm() > kMaxStepAngle) w *= kMaxStepAngle / w.norm();
  const Eigen::Matrix3d dR =
      w.norm() > 0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                   : Eigen::Matrix3d::Identity();
  pose.R = dR * pose.R;
  pose.t = dR * (pose.t - centre) + centre + x.tail<3>();
  // Re-orthonormalise: many small steps in double drift only slightly, but a rotation it is.
  pose.R = Eigen::Quaterniond(pose.R).normalized().toRotationMatrix();
}

// How many of the poses, from the first, the memo holds (bit for bit the same inputs).
std::size_t known_prefix(const RefineMemo& memo, const std::vector<PoseToRefine>& poses) {
  std::size_t k = 0;
  while (k < memo.inputs.size() && k < poses.size() && memo.inputs[k].R == poses[k].R &&
         memo.inputs[k].t == poses[k].t)
    ++k;
  return k;
}

}  // namespace

void check(const RefineOptions& o) {
  const auto bad = [](double v, double lo, double hi) { return !(v >= lo && v <= hi); };
  if (o.iterations > 100) throw InputError(fmt::format("refine iterations {} must be in [0, 100]", o.iterations));
  if (bad(o.gate_start_ratio, 1e-4, 10))
    throw InputError(fmt::format("refine gate {} must be in [1e-4, 10]", o.gate_start_ratio));
  if (bad(o.tolerance_ratio, 1e-4, 1))
    throw InputError(fmt::format("verify tolerance {} must be in [1e-4, 1]", o.tolerance_ratio));
  if (bad(o.noise_factor, 0, 100))
    throw InputError(fmt::format("verify noise factor {} must be in [0, 100]", o.noise_factor));
  if (bad(o.outline_ratio, 0, 1))
    throw InputError(fmt::format("outline tolerance {} must be in [0, 1]", o.outline_ratio));
  if (bad(o.through_weight, 0, 100))
    throw InputError(fmt::format("see-through weight {} must be in [0, 100]", o.through_weight));
  if (bad(o.area_scale, 0, 10))
    throw InputError(fmt::format("seen-area scale {} must be in [0, 10]", o.area_scale));
  if (bad(o.ray_band_ratio, 0, 1))
    throw InputError(fmt::format("ray test band {} must be in [0, 1]", o.ray_band_ratio));
  if (bad(o.noise, 0, 1e6))
    throw InputError(fmt::format("depth noise {} mm must be finite and not negative", o.noise));
  if (bad(o.min_support_ratio, 0, 1))
    throw InputError(fmt::format("verify min support {} must be in [0, 1]", o.min_support_ratio));
}

Eigen::Matrix<double, 6, 1> gauss_newton_step(const FitSums& s) {
  Eigen::Matrix<double, 6, 6> h = s.jtj;
  const double trace = h.trace();
  if (!(trace > 0) || !std::isfinite(trace)) return Eigen::Matrix<double, 6, 1>::Zero();
  // Levenberg damping: directions the surface does not constrain (sliding along a plane,
  // turning about a shaft's axis) stay where voting put them instead of drifting.
  h.diagonal().array() += 1e-4 * trace / 6.0;
  const Eigen::Matrix<double, 6, 1> x = h.ldlt().solve(s.jtr);
  return x.allFinite() ? x : Eigen::Matrix<double, 6, 1>::Zero();
}

std::vector<RefinedPose> refine_and_verify(const FitSumsFn& sums_of, const bp_camera& cam,
                                           const FitGeometry& g, std::uint32_t model_points,
                                           const std::vector<PoseToRefine>& input,
                                           const RefineOptions& opt, RefineMemo* memo) {
  check(opt);
  std::vector<PoseToRefine> poses = input;
  std::vector<RefinedPose> out(poses.size());
  std::vector<bool> active(poses.size(), true);
  const std::size_t known = memo ? known_prefix(*memo, input) : 0;
  for (std::size_t k = 0; k < known; ++k) {
    poses[k] = memo->refined[k];
    out[k].iterations = memo->iterations[k];
    out[k].reason = memo->reasons[k];
    active[k] = false;
  }
  float tolerance = opt.tolerance_ratio * g.diameter;
  const float gate_start = opt.gate_start_ratio * g.diameter;
  const float gate_end = std::min(gate_start, 2.0f * tolerance);
  std::vector<bp_pose_fit> fits(poses.size());
  std::vector<std::size_t> index;  // fits[i] is pose index[i]
  for (std::uint32_t it = 0; it < opt.iterations; ++it) {
    const float gate = opt.iterations == 1
                           ? gate_end
                           : float(gate_start * std::pow(double(gate_end) / gate_start,
                                                         double(it) / (opt.iterations - 1)));
    fits.clear();
    index.clear();
    for (std::size_t k = 0; k < poses.size(); ++k) {
      if (!active[k]) continue;
      fits.push_back(
          make_pose_fit(poses[k].R, poses[k].t, cam, g, thresholds(g, tolerance, gate, opt)));
      index.push_back(k);
    }
    if (fits.empty()) break;
    const std::vector<FitSums> sums = sums_of(fits);
    for (std::size_t i = 0; i < fits.size(); ++i) {
      const std::size_t k = index[i];
      if (sums[i].used < opt.min_pairs) {
        out[k].reason = fmt::format("refinement stopped after {} steps: {} point pairs, fewer than {}",
                                    it, sums[i].used, opt.min_pairs);
        active[k] = false;
        continue;
      }
      const Eigen::Vector3d centre(fits[i].centre[0], fits[i].centre[1], fits[i].centre[2]);
      apply_step(gauss_newton_step(sums[i]), centre, poses[k]);
      out[k].iterations = it + 1;
    }
  }

  if (memo) {
    memo->inputs = input;
    memo->refined = poses;
    memo->iterations.resize(poses.size());
    memo->reasons.resize(poses.size());
    for (std::size_t k = known; k < poses.size(); ++k)
      memo->iterations[k] = out[k].iterations, memo->reasons[k] = out[k].reason;
  }
  const auto final_sums = [&](float tol, float gate, float outline, bool residuals) {
    FitThresholds th = thresholds(g, tol, gate, opt);
    th.outline = outline;
    th.residuals = residuals;
    fits.clear();
    for (const PoseToRefine& p : poses) fits.push_back(make_pose_fit(p.R, p.t, cam, g, th));
    return sums_of(fits);
  };
  // The tolerance follows the sensor's noise, as the best-fitting pose shows it (its residual's
  // weighted RMS): at 5 % noise the fixed 0.04 d lies inside the noise, and right poses scored
  // little above wrong ones. It widens to at most three times the fixed one, never narrows.
  float final_gate = gate_end;
  if (opt.noise_factor > 0) {
    // Residuals within a wide gate (4 tolerances), Tukey-weighted: their weighted mean square.
    // The weights' sum is the trace of the translation block (unit normals).
    double noise = INFINITY;
    for (const FitSums& s : final_sums(tolerance, 4 * tolerance, 0.0f, false)) {
      const double weight = s.jtj(3, 3) + s.jtj(4, 4) + s.jtj(5, 5);
      if (s.used >= opt.min_pairs && weight > 0) noise = std::min(noise, std::sqrt(s.cost / weight));
    }
    const float wide = std::isfinite(noise)
                           ? std::clamp(float(opt.noise_factor * noise), tolerance, 3 * tolerance)
                           : tolerance;
    if (wide > 1.05f * tolerance) {
      tolerance = wide;
      final_gate = 2 * tolerance;
    }
  }
  // The dead band of the patch test: a quarter of the fixed tolerance (0.01 d by default), the
  // size of a right pose's leftover error; it does not widen with the noise, the significance
  // test does that.
  PatchTestOptions patch_opt;
  patch_opt.dead_band = 0.25f * opt.tolerance_ratio * g.diameter;
  const bool patch_test_on = g.patches.count > 0;
  const bool ray_test_on = opt.ray_band_ratio > 0 && !g.points.empty() &&
                           g.points.size() == g.normals.size() && g.points.size() == model_points;
  const bool area_test_on = opt.area_scale > 0 && g.mean_area > 0 &&
                            g.points.size() == model_points && g.normals.size() == model_points;
  const bool keep_measured = opt.keep_measured && g.points.size() == model_points &&
                             g.normals.size() == model_points;
  const std::vector<FitSums> sums = final_sums(tolerance, final_gate, opt.outline_ratio * g.diameter,
                                               patch_test_on || ray_test_on || keep_measured ||
                                                   area_test_on);
  const double min_support = double(opt.min_support_ratio) * model_points;
  // The ray test (ray_spread.hpp): each pose's spread along the rays; the image's noise is the
  // least among the poses with enough points.
  std::vector<RaySpread> ray(poses.size());
  RaySpread ray_noise;
  if (ray_test_on) {
    for (std::size_t k = 0; k < poses.size(); ++k)
      if (sums[k].residuals.size() == model_points)
        ray[k] = ray_spread(
            ray_residuals(sums[k].residuals, poses[k].R, poses[k].t, g.points, g.normals));
    ray_noise = ray_floor(ray);
  }
  for (std::size_t k = 0; k < poses.size(); ++k) {
    RefinedPose& r = out[k];
    const FitSums& s = sums[k];
    r.R = poses[k].R;
    r.t = poses[k].t;
    r.visible = s.visible();
    r.missing = s.count[BP_FIT_MISSING];
    r.inliers = s.count[BP_FIT_INLIER];
    r.see_through = s.count[BP_FIT_SEE_THROUGH];
    r.occluded = s.count[BP_FIT_OCCLUDED];
    r.tolerance = tolerance;
    r.outline_continue = s.outline_continue;
    r.outline_step = s.outline_step;
    if (keep_measured && s.residuals.size() == model_points)
      r.measured = measured_points(s.residuals, r.R, r.t, g.points, g.normals, cam);
    if (r.visible == 0) {
      r.score = 0;
      r.reason = "no model surface visible at this pose";
    } else if (r.visible == r.missing) {
      r.score = 0;
      r.reason = "no depth where the model would be seen";
    } else {
      // Missing depth counts half: neither for the pose nor fully against it, so that a pose
      // parked over a shadow or beyond the sensor's range is not judged on a few points alone.
      const double support = double(r.visible) - 0.5 * double(r.missing);
      const double denominator = std::max(support, std::max(min_support, 1.0));
      r.score = s.agreement / denominator;
      // The see-through cost: the sensor saw past the part where the pose puts it.
      if (opt.through_weight > 0)
        r.score *= std::max(0.0, 1.0 - double(opt.through_weight) * double(r.see_through) /
                                           denominator);
      const std::uint32_t outline = s.outline_continue + s.outline_step;
      if (outline > 0) r.score *= double(s.outline_step) / double(outline);
      if (patch_test_on) {
        const PatchTest pt = patch_test(s.residuals, g.patches, patch_opt);
        r.patches_tested = pt.tested;
        r.patches_biased = pt.biased;
        r.score *= pt.factor();
      }
      if (area_test_on && s.classes.size() == model_points) {
        r.area_tested = true;
        r.area_share = seen_area(s.classes, r.R, r.t, g.points, g.normals) / g.mean_area;
        r.score *= area_factor(r.area_share, opt.area_scale);
      }
      // Fewer residuals than refinement needs: too few to tell a spread from the noise.
      if (ray_test_on && ray_noise.n > 0 && ray[k].n >= opt.min_pairs) {
        r.ray_tested = true;
        r.ray_excess = ray_excess(ray[k], ray_noise);
        r.score *= excess_factor(r.ray_excess, double(opt.ray_band_ratio) * g.diameter);
      }
    }
  }
  return out;
}

}  // namespace binpick
