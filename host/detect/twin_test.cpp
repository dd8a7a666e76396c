#include "host/detect/twin_test.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "host/detect/ray_test.hpp"

namespace binpick {

TwinEvidence twin_evidence(std::span<const float> residuals, const Eigen::Matrix3d& R,
                           const Eigen::Vector3d& t, const PointCloud& probes,
                           std::span<const std::uint32_t> probe_twin, std::uint32_t which,
                           double gate) {
  if (residuals.size() != probes.points.size() || probe_twin.size() != probes.points.size() ||
      probes.normals.size() != probes.points.size())
    throw std::logic_error("twin test: one residual, normal and look-alike per probe expected");
  double sum = 0, sum2 = 0;
  std::size_t n = 0;
  for (std::size_t j = 0; j < residuals.size(); ++j) {
    if (probe_twin[j] != which) continue;
    const float r = residuals[j];
    double excess = 0;
    if (std::isnan(r) || r == INFINITY) continue;  // nothing seen, or something in front
    if (r == -INFINITY) {
      excess = gate;  // seen through, beyond the gate
    } else {
      const Eigen::Vector3d q = R * probes.points[j].cast<double>() + t;
      const Eigen::Vector3d nq = R * probes.normals[j].cast<double>();
      const double c = -nq.dot(q) / (q.norm() * nq.norm());
      if (!(c > 0.0)) continue;  // the kernel gives terms only to probes facing the camera
      // r = nq . (p - q) is negative where the sensor saw farther along the ray.
      excess = std::clamp(-double(r) / c, -gate, gate);
    }
    sum += excess;
    sum2 += excess * excess;
    ++n;
  }
  TwinEvidence e;
  e.n = n;
  if (n == 0) return e;
  e.mean = sum / double(n);
  const double variance = n > 1 ? std::max(0.0, (sum2 - sum * e.mean) / double(n - 1)) : 0.0;
  e.standard_error = std::sqrt(variance / double(n));
  return e;
}

double twin_excess(const TwinEvidence& e, std::size_t min_probes) {
  if (e.n < std::max<std::size_t>(min_probes, 1)) return 0;
  return std::max(0.0, e.mean - 2.0 * e.standard_error);
}

void twin_test(const FitSumsFn& sums_of, const bp_camera& cam, const FitGeometry& g,
               const TwinProbeModel& model, std::vector<RefinedPose>& poses,
               const TwinTestOptions& opt) {
  if (!(opt.band_ratio > 0) || model.probes.points.empty() || model.twins == 0) return;
  std::vector<bp_pose_fit> fits;
  std::vector<std::size_t> index;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (!(poses[k].score > 0)) continue;
    FitThresholds th;
    th.gate = th.tolerance = poses[k].tolerance;
    th.slack = std::max(2.0f * g.voxel_size, th.tolerance);  // as refinement's z-buffer
    th.residuals = true;
    fits.push_back(make_pose_fit(poses[k].R, poses[k].t, cam, g, th));
    index.push_back(k);
  }
  if (fits.empty()) return;
  const std::vector<FitSums> sums = sums_of(fits);
  const double band = double(opt.band_ratio) * g.diameter;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    RefinedPose& r = poses[index[i]];
    const std::vector<float>& all = sums[i].residuals;
    if (all.size() != model.fit_points + model.probes.points.size())
      throw std::logic_error("twin test: the probe pass gave no residual per point");
    const std::span<const float> probe_residuals(all.data() + model.fit_points,
                                                 model.probes.points.size());
    for (std::uint32_t s = 0; s < model.twins; ++s) {
      const TwinEvidence e = twin_evidence(probe_residuals, r.R, r.t, model.probes,
                                           model.probe_twin, s, r.tolerance);
      if (e.n < opt.min_probes) continue;
      r.twin_tested = true;
      r.twin_excess = std::max(r.twin_excess, twin_excess(e, opt.min_probes));
    }
    r.score *= excess_factor(r.twin_excess, band);
  }
}

}  // namespace binpick
