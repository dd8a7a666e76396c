#include "host/detect/pose_cluster.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <span>

#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick {
namespace {

float min_cos_half(const ClusterOptions& opt) {
  return float(std::cos(0.5 * double(opt.max_angle_deg) * std::numbers::pi / 180.0));
}

float max_dist2(const ClusterOptions& opt) { return opt.max_distance * opt.max_distance; }

}  // namespace

void check(const ClusterOptions& opt) {
  if (!(std::isfinite(opt.max_distance) && opt.max_distance >= 0))
    throw InputError(fmt::format("cluster distance {} mm must be finite and >= 0", opt.max_distance));
  if (!(opt.max_angle_deg >= 0 && opt.max_angle_deg <= 180))
    throw InputError(fmt::format("cluster angle {} must be in [0, 180] degrees", opt.max_angle_deg));
}

bool pose_compatible(const PoseCandidate& a, const PoseCandidate& b, float max_dist2,
                     float min_cos_half) {
  const float dx = a.t.x() - b.t.x(), dy = a.t.y() - b.t.y(), dz = a.t.z() - b.t.z();
  const float dist2 = dx * dx + dy * dy + dz * dz;
  const float dot = a.q.x() * b.q.x() + a.q.y() * b.q.y() + a.q.z() * b.q.z() + a.q.w() * b.q.w();
  return dist2 <= max_dist2 && std::fabs(dot) >= min_cos_half;
}

PoseCompatibility pose_compatibility(ocl::Device& dev, const std::vector<PoseCandidate>& poses,
                                     const ClusterOptions& opt) {
  check(opt);
  const std::size_t n = poses.size();
  if (n > kMaxClusterPoses)
    throw InputError(fmt::format("{} poses to cluster, at most {}", n, kMaxClusterPoses));
  PoseCompatibility out;
  out.n = n;
  if (n == 0) return out;
  std::vector<cl_float4> q(n), t(n);
  std::vector<std::uint32_t> votes(n);
  for (std::size_t i = 0; i < n; ++i) {
    q[i] = {{poses[i].q.x(), poses[i].q.y(), poses[i].q.z(), poses[i].q.w()}};
    t[i] = {{poses[i].t.x(), poses[i].t.y(), poses[i].t.z(), 0.0f}};
    votes[i] = poses[i].votes;
  }
  ocl::Buffer<cl_float4> qb(dev, std::span<const cl_float4>(q), CL_MEM_READ_ONLY);
  ocl::Buffer<cl_float4> tb(dev, std::span<const cl_float4>(t), CL_MEM_READ_ONLY);
  ocl::Buffer<std::uint32_t> vb(dev, std::span<const std::uint32_t>(votes), CL_MEM_READ_ONLY);
  ocl::Buffer<std::uint8_t> compatible(dev, n * n);
  ocl::Buffer<std::uint32_t> scores(dev, n);
  cl::Kernel kernel = dev.kernel("pose_cluster.cl", "pose_compatibility");
  ocl::launch(dev, kernel, n, qb, tb, vb, static_cast<std::uint32_t>(n), max_dist2(opt),
              min_cos_half(opt), compatible, scores);
  out.compatible = compatible.read(dev);
  out.scores = scores.read(dev);
  return out;
}

PoseCompatibility pose_compatibility_reference(const std::vector<PoseCandidate>& poses,
                                               const ClusterOptions& opt) {
  check(opt);
  const std::size_t n = poses.size();
  PoseCompatibility out;
  out.n = n;
  out.compatible.assign(n * n, 0);
  out.scores.assign(n, 0);
  const float d2 = max_dist2(opt), c = min_cos_half(opt);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      if (pose_compatible(poses[i], poses[j], d2, c)) {
        out.compatible[i * n + j] = 1;
        out.scores[i] += poses[j].votes;
      }
  return out;
}

std::vector<PoseCluster> group_poses(const std::vector<PoseCandidate>& poses,
                                     const PoseCompatibility& m) {
  const std::size_t n = poses.size();
  if (m.n != n || m.compatible.size() != n * n || m.scores.size() != n)
    throw std::logic_error("pose compatibility does not match the poses");
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (m.scores[a] != m.scores[b]) return m.scores[a] > m.scores[b];
    return poses[a].votes > poses[b].votes;
  });
  std::vector<bool> grouped(n, false);
  std::vector<PoseCluster> clusters;
  for (std::uint32_t centre : order) {
    if (grouped[centre]) continue;
    PoseCluster c;
    c.centre = centre;
    const Eigen::Quaterniond qc = poses[centre].q.cast<double>();
    Eigen::Vector4d qsum = Eigen::Vector4d::Zero();
    Eigen::Vector3d tsum = Eigen::Vector3d::Zero();
    for (std::uint32_t j = 0; j < n; ++j) {
      if (grouped[j] || !m.compatible[std::size_t(centre) * n + j]) continue;
      grouped[j] = true;
      c.members.push_back(j);
      const double w = poses[j].votes;
      Eigen::Quaterniond q = poses[j].q.cast<double>();
      if (q.dot(qc) < 0) q.coeffs() = -q.coeffs();  // the same rotation, same hemisphere
      qsum += w * q.coeffs();
      tsum += w * poses[j].t.cast<double>();
      c.votes += poses[j].votes;
    }
    if (c.members.empty()) {  // a pose incompatible with itself: only with a NaN
      grouped[centre] = true;
      continue;
    }
    if (c.votes > 0 && qsum.norm() > 0) {
      c.q.coeffs() = qsum.normalized();
      c.t = tsum / double(c.votes);
    } else {
      c.q = qc;
      c.t = poses[centre].t.cast<double>();
    }
    clusters.push_back(std::move(c));
  }
  std::stable_sort(clusters.begin(), clusters.end(),
                   [](const PoseCluster& a, const PoseCluster& b) { return a.votes > b.votes; });
  return clusters;
}

std::vector<PoseCluster> cluster_poses(ocl::Device& dev, const std::vector<PoseCandidate>& input,
                                       const ClusterOptions& opt, StageTimings* timings) {
  Stopwatch clock;
  std::vector<PoseCandidate> kept;
  const std::vector<PoseCandidate>* poses = &input;
  if (input.size() > kMaxClusterPoses) {
    std::vector<std::uint32_t> order(input.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return input[a].votes > input[b].votes;
    });
    order.resize(kMaxClusterPoses);
    std::sort(order.begin(), order.end());
    for (std::uint32_t i : order) kept.push_back(input[i]);
    poses = &kept;
  }
  // Compare the posed centres, not the posed origins (see ClusterOptions::centre).
  std::vector<PoseCandidate> centred = *poses;
  for (PoseCandidate& p : centred) p.t += p.q * opt.centre;
  const PoseCompatibility m = pose_compatibility(dev, centred, opt);
  std::vector<PoseCluster> clusters = group_poses(centred, m);
  for (PoseCluster& c : clusters) c.t -= c.q * opt.centre.cast<double>();
  if (timings) timings->push_back({"cluster", clock.lap()});
  return clusters;
}

}  // namespace binpick
