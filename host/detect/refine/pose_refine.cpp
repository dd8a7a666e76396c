#include "host/detect/refine/pose_refine.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick {
namespace {

// A step rotates by at most this (radians): a step is a linearisation, trusted only nearby.
constexpr double kMaxStepAngle = 0.25;

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

FitThresholds fit_thresholds(const FitGeometry& g, float tolerance, float gate,
                             const RefineOptions& opt) {
  FitThresholds th;
  th.gate = gate;
  th.tolerance = tolerance;
  th.slack = zbuffer_slack(g, th.tolerance);
  if (opt.near_gate) th.near_gate = bp_near_gate(gate, tolerance, opt.noise);
  return th;
}

void check(const RefineOptions& o) {
  const auto bad = [](double v, double lo, double hi) { return !(v >= lo && v <= hi); };
  if (o.iterations > 100) throw InputError(fmt::format("refine iterations {} must be in [0, 100]", o.iterations));
  if (bad(o.gate_start_ratio, 1e-4, 10))
    throw InputError(fmt::format("refine gate {} must be in [1e-4, 10]", o.gate_start_ratio));
  if (bad(o.tolerance_ratio, 1e-4, 1))
    throw InputError(fmt::format("verify tolerance {} must be in [1e-4, 1]", o.tolerance_ratio));
  if (bad(o.noise, 0, 1e6))
    throw InputError(fmt::format("depth noise {} mm must be finite and not negative", o.noise));
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

std::vector<RefinedPose> refine_poses(const FitSumsFn& sums_of, const bp_camera& cam,
                                      const FitGeometry& g, const std::vector<PoseToRefine>& input,
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
  const float tolerance = opt.tolerance_ratio * g.diameter;
  const float gate_start = opt.gate_start_ratio * g.diameter;
  const float gate_end = std::min(gate_start, 2.0f * tolerance);
  std::vector<bp_pose_fit> fits;
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
          make_pose_fit(poses[k].R, poses[k].t, cam, g, fit_thresholds(g, tolerance, gate, opt)));
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
  for (std::size_t k = 0; k < poses.size(); ++k) out[k].R = poses[k].R, out[k].t = poses[k].t;
  return out;
}

}  // namespace binpick
