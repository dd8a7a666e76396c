#include "host/detect/verify/lookalike_holes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "host/detect/verify/edge_step.hpp"
#include "host/detect/verify/ray_spread.hpp"

namespace binpick {
namespace {

// A probe without depth counts only where it faces the camera within 60 degrees.
constexpr double kMissingCos = 0.5;

}  // namespace

ProbeEvidence probe_evidence(std::span<const float> residuals, std::span<const std::uint8_t> classes,
                           const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                           const PointCloud& probes, std::span<const std::uint32_t> probe_lookalike,
                           std::uint32_t which, double gate, NoDepth no_depth) {
  const std::size_t n_probes = probes.points.size();
  if (residuals.size() != n_probes || classes.size() != n_probes || probe_lookalike.size() != n_probes ||
      probes.normals.size() != n_probes)
    throw std::logic_error("look-alike holes: one residual, class, normal and look-alike per probe expected");
  double sum = 0, sum2 = 0;
  ProbeEvidence e;
  for (std::size_t j = 0; j < n_probes; ++j) {
    if (probe_lookalike[j] != which) continue;
    const float r = residuals[j];
    const std::uint8_t cls = classes[j];
    double excess = 0;
    if (cls == BP_FIT_HIDDEN) continue;
    const Eigen::Vector3d q = R * probes.points[j].cast<double>() + t;
    const Eigen::Vector3d nq = R * probes.normals[j].cast<double>();
    // The cosine between the probe's normal and the ray to the camera (> 0.17 for a visible one).
    const double c = ray_cosine(q, nq);
    if (!(c > 0.0)) continue;
    if (cls == BP_FIT_MISSING) {
      // A surface seen obliquely often gives no depth on real material; one facing the camera
      // gives depth unless shadowed, which the pose's own share without depth stands for.
      if (c < kMissingCos) continue;
      ++e.missing;
      if (no_depth == NoDepth::neutral) continue;
      excess = gate;
    } else if (std::isfinite(r)) {
      // r = nq . (p - q) is negative where the sensor saw farther along the ray.
      excess = std::clamp(-double(r) / c, -gate, gate);
    } else if (cls == BP_FIT_SEE_THROUGH) {
      excess = gate;  // seen through, beyond the gate
    } else {
      continue;  // something in front, beyond the gate (or an inlier at the gate's edge)
    }
    sum += excess;
    sum2 += excess * excess;
    ++e.n;
  }
  if (e.n == 0) return e;
  e.mean = sum / double(e.n);
  const double variance = e.n > 1 ? std::max(0.0, (sum2 - sum * e.mean) / double(e.n - 1)) : 0.0;
  e.standard_error = std::sqrt(variance / double(e.n));
  return e;
}

double seen_excess(const ProbeEvidence& with_depth, std::size_t min_probes) {
  if (with_depth.n < std::max<std::size_t>(min_probes, 1)) return 0;
  return std::max(0.0, with_depth.mean - 2.0 * with_depth.standard_error);
}

double holes_excess(const ProbeEvidence& e, std::size_t min_probes, double missing_rate, double gate) {
  if (e.n < std::max<std::size_t>(min_probes, 1)) return 0;
  // The probes' share without depth is one draw of the pose's own share m, not e.n independent
  // ones (lookalike_holes.hpp): its spread, sqrt(m (1 - m)) gates, joins the standard error.
  const double m = std::clamp(missing_rate, 0.0, 1.0);
  const double spread = m * (1.0 - m) * gate * gate;
  const double error = std::sqrt(e.standard_error * e.standard_error + spread);
  return std::max(0.0, e.mean - m * gate - 2.0 * error);
}

void lookalike_holes(const FitSumsFn& sums_of, const bp_camera& cam, const FitGeometry& g,
                     const ProbeModel& model, std::vector<VerifiedPose>& poses,
                     const LookalikeHolesOptions& opt) {
  const bool holes_on = opt.band_ratio > 0 && model.lookalikes > 0;
  const bool edges_on = opt.edge_scale > 0 && model.edge_probes > 0;
  if (model.probes.points.empty() || !(holes_on || edges_on)) return;
  RefineOptions near;  // the near gate, as refinement's last steps have it
  near.near_gate = opt.near_gate;
  near.noise = opt.noise;
  std::vector<bp_pose_fit> fits;
  std::vector<std::size_t> index;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (!(poses[k].score() > 0)) continue;
    // At the pose's verification tolerance, as the gate too.
    const float tolerance = poses[k].evidence.tolerance;
    FitThresholds th = fit_thresholds(g, tolerance, tolerance, near);
    th.residuals = true;
    fits.push_back(make_pose_fit(poses[k].R, poses[k].t, cam, g, th));
    index.push_back(k);
  }
  if (fits.empty()) return;
  const std::vector<FitSums> sums = sums_of(fits);
  const double band = double(opt.band_ratio) * g.diameter;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    VerifiedPose& v = poses[index[i]];
    PoseEvidence& e = v.evidence;
    const std::vector<float>& all = sums[i].residuals;
    if (all.size() != model.fit_points + model.probes.points.size() ||
        sums[i].classes.size() != all.size())
      throw std::logic_error("look-alike holes: the probe pass gave no residual per point");
    const std::size_t probes = model.probes.points.size();
    const std::span<const float> probe_residuals(all.data() + model.fit_points, probes);
    const std::span<const std::uint8_t> probe_classes(sums[i].classes.data() + model.fit_points,
                                                      probes);
    const double missing_rate = e.visible > 0 ? double(e.missing) / double(e.visible) : 0.0;
    for (std::uint32_t s = 0; holes_on && s < model.lookalikes; ++s) {
      const ProbeEvidence all_probes =
          probe_evidence(probe_residuals, probe_classes, v.R, v.t, model.probes,
                         model.probe_lookalike, s, e.tolerance);
      if (all_probes.n < opt.min_probes) continue;
      e.lookalike_tested = true;
      // The probes with depth alone, too: under patchy dropout the share without depth says
      // little, and those seen through are evidence however many others have none.
      const ProbeEvidence seen = probe_evidence(probe_residuals, probe_classes, v.R, v.t,
                                                model.probes, model.probe_lookalike, s,
                                                e.tolerance, NoDepth::neutral);
      e.lookalike_excess =
          std::max({e.lookalike_excess,
                    holes_excess(all_probes, opt.min_probes, missing_rate, e.tolerance),
                    seen_excess(seen, opt.min_probes)});
    }
    v.breakdown[kLookalikeHoles] = excess_factor(e.lookalike_excess, band);
    if (!edges_on) continue;
    // No depth beyond an edge says nothing (edge_step.hpp says why).
    const ProbeEvidence edges = probe_evidence(probe_residuals, probe_classes, v.R, v.t,
                                               model.probes, model.probe_lookalike,
                                               model.lookalikes, e.tolerance, NoDepth::neutral);
    if (edges.n < opt.min_probes) continue;
    e.edge_tested = true;
    e.edge_step = edge_step(edges);
    v.breakdown[kEdgeStep] = edge_factor(e.edge_step, opt.edge_scale, e.tolerance);
  }
}

}  // namespace binpick
