#include "host/detect/cluster/pose_cluster.hpp"

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

// The axis modes compare posed axes: the cosine of the whole angle, not of its half.
float min_cos_axis(const ClusterOptions& opt) {
  return float(std::cos(double(opt.max_angle_deg) * std::numbers::pi / 180.0));
}

bool axis_mode(std::uint32_t mode) {
  return mode == BP_CLUSTER_AXIS || mode == BP_CLUSTER_AXIS_EITHER;
}

bp_quat quat_of(const Eigen::Quaternionf& q) { return {q.x(), q.y(), q.z(), q.w()}; }

// The posed symmetry axis R a of each pose (axis modes): the kernel and the reference get the
// same floats.
std::vector<Eigen::Vector3f> posed_axes(const std::vector<PoseCandidate>& poses,
                                        const ClusterSymmetry& sym) {
  std::vector<Eigen::Vector3f> out;
  if (!axis_mode(sym.mode)) return out;
  out.reserve(poses.size());
  for (const PoseCandidate& p : poses) out.push_back(p.q * sym.axis);
  return out;
}

// The kernel's predicate, operation for operation (kernels/pose_cluster.cl).
bool compatible(const PoseCandidate& a, const PoseCandidate& b, const Eigen::Vector3f* axis_a,
                const Eigen::Vector3f* axis_b, const std::vector<bp_quat>& rotations,
                std::uint32_t mode, float max_dist2, float min_cos_half, float min_cos_axis) {
  const float dx = a.t.x() - b.t.x(), dy = a.t.y() - b.t.y(), dz = a.t.z() - b.t.z();
  const float dist2 = dx * dx + dy * dy + dz * dz;
  bool ok = dist2 <= max_dist2;
  if (ok && mode == BP_CLUSTER_ROTATIONS) {
    const bp_quat qa = quat_of(a.q), qb = quat_of(b.q);
    ok = std::fabs(bp_quat_dot(qa, qb)) >= min_cos_half;
    if (!ok && !rotations.empty()) {
      const bp_quat r = bp_quat_relative(qa, qb);
      for (std::size_t k = 0; k < rotations.size() && !ok; ++k)
        ok = std::fabs(bp_quat_dot(r, rotations[k])) >= min_cos_half;
    }
  } else if (ok && mode != BP_CLUSTER_ANY) {
    const Eigen::Vector3f& u = *axis_a;
    const Eigen::Vector3f& v = *axis_b;
    ok = bp_cluster_axes_close(u.x() * v.x() + u.y() * v.y() + u.z() * v.z(), mode, min_cos_axis);
  }
  return ok;
}

std::vector<bp_quat> kernel_rotations(const ClusterSymmetry& sym) {
  std::vector<bp_quat> out;
  for (const auto& q : sym.rotations) out.push_back(quat_of(q));
  return out;
}

}  // namespace

ClusterSymmetry cluster_symmetry(const PartSymmetries& s) {
  ClusterSymmetry out;
  for (const auto& c : s.continuous)
    if (!c.axis.allFinite() || !(c.axis.norm() > 0) || !c.offset.allFinite())
      throw InputError("a continuous symmetry's axis must be finite and not zero");
  for (const auto& m : s.discrete) {
    const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
    if (!m.allFinite() || !(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-4) ||
        !(R.determinant() > 0))
      throw InputError("a discrete symmetry's 3x3 part must be a rotation");
  }
  if (!s.continuous.empty()) {
    const Eigen::Vector3d a = s.continuous.front().axis.normalized();
    out.axis = a.cast<float>();
    out.mode = BP_CLUSTER_AXIS;
    for (const auto& c : s.continuous)
      if (c.axis.normalized().cross(a).norm() > 1e-6) out.mode = BP_CLUSTER_ANY;  // as eval does
    if (out.mode == BP_CLUSTER_ANY) return out;
    for (const auto& m : s.discrete) {
      const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
      if (a.dot(R * a) < 0) {
        out.mode = BP_CLUSTER_AXIS_EITHER;
        out.flip = Eigen::Quaterniond(R).normalized();
        break;
      }
    }
    return out;
  }
  for (const auto& m : s.discrete) {
    const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
    const Eigen::Quaterniond q = Eigen::Quaterniond(R).normalized();
    if (std::fabs(q.w()) > 1 - 1e-12) continue;  // the identity
    out.rotations.push_back(q.cast<float>());
  }
  if (out.rotations.size() > BP_CLUSTER_MAX_SYMMETRIES)
    throw InputError(fmt::format(
        "{} discrete symmetries: pose clustering takes at most {} besides the identity",
        out.rotations.size(), BP_CLUSTER_MAX_SYMMETRIES));
  return out;
}

void check(const ClusterOptions& opt) {
  if (!(std::isfinite(opt.max_distance) && opt.max_distance >= 0))
    throw InputError(fmt::format("cluster distance {} mm must be finite and >= 0", opt.max_distance));
  if (!(opt.max_angle_deg >= 0 && opt.max_angle_deg <= 180))
    throw InputError(fmt::format("cluster angle {} must be in [0, 180] degrees", opt.max_angle_deg));
  cluster_symmetry(opt.symmetries);
}

bool pose_compatible(const PoseCandidate& a, const PoseCandidate& b, float max_dist2,
                     float min_cos_half) {
  return compatible(a, b, nullptr, nullptr, {}, BP_CLUSTER_ROTATIONS, max_dist2, min_cos_half,
                    1.0f);
}

Eigen::Quaterniond nearest_equivalent(const Eigen::Quaterniond& q, const Eigen::Quaterniond& centre,
                                      const ClusterSymmetry& sym) {
  if (sym.mode == BP_CLUSTER_ANY) return centre;
  std::vector<Eigen::Quaterniond> options{q};
  if (sym.mode == BP_CLUSTER_ROTATIONS) {
    for (const auto& g : sym.rotations) options.push_back(q * g.cast<double>());
  } else {
    if (sym.mode == BP_CLUSTER_AXIS_EITHER) options.push_back(q * sym.flip);
    // q C(theta), C a turn about the axis: (q C) . centre = C . (q^-1 centre) is largest at
    // theta / 2 = atan2(r_vec . a, r_w) with r = q^-1 centre.
    const Eigen::Vector3d a = sym.axis.cast<double>();
    for (auto& o : options) {
      const Eigen::Quaterniond r = o.conjugate() * centre;
      const double theta = 2 * std::atan2(r.vec().dot(a), r.w());
      o = o * Eigen::Quaterniond(Eigen::AngleAxisd(theta, a));
    }
  }
  Eigen::Quaterniond best = options.front();
  for (const auto& o : options)
    if (std::fabs(o.dot(centre)) > std::fabs(best.dot(centre))) best = o;
  if (best.dot(centre) < 0) best.coeffs() = -best.coeffs();  // the same rotation, same hemisphere
  return best;
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
  const ClusterSymmetry sym = cluster_symmetry(opt.symmetries);
  const std::vector<Eigen::Vector3f> axes = posed_axes(poses, sym);
  // Buffers of at least one element: OpenCL has no empty buffers.
  std::vector<cl_float4> q(n), t(n), a(std::max<std::size_t>(axes.size(), 1), cl_float4{});
  std::vector<std::uint32_t> votes(n);
  for (std::size_t i = 0; i < n; ++i) {
    q[i] = {{poses[i].q.x(), poses[i].q.y(), poses[i].q.z(), poses[i].q.w()}};
    t[i] = {{poses[i].t.x(), poses[i].t.y(), poses[i].t.z(), 0.0f}};
    votes[i] = poses[i].votes;
  }
  for (std::size_t i = 0; i < axes.size(); ++i)
    a[i] = {{axes[i].x(), axes[i].y(), axes[i].z(), 0.0f}};
  std::vector<cl_float4> g(std::max<std::size_t>(sym.rotations.size(), 1), cl_float4{});
  for (std::size_t k = 0; k < sym.rotations.size(); ++k) {
    const auto& r = sym.rotations[k];
    g[k] = {{r.x(), r.y(), r.z(), r.w()}};
  }
  ocl::Buffer<cl_float4> qb(dev, std::span<const cl_float4>(q), CL_MEM_READ_ONLY);
  ocl::Buffer<cl_float4> tb(dev, std::span<const cl_float4>(t), CL_MEM_READ_ONLY);
  ocl::Buffer<cl_float4> ab(dev, std::span<const cl_float4>(a), CL_MEM_READ_ONLY);
  ocl::Buffer<std::uint32_t> vb(dev, std::span<const std::uint32_t>(votes), CL_MEM_READ_ONLY);
  ocl::Buffer<cl_float4> gb(dev, std::span<const cl_float4>(g), CL_MEM_READ_ONLY);
  ocl::Buffer<std::uint8_t> compatible(dev, n * n);
  ocl::Buffer<std::uint32_t> scores(dev, n);
  cl::Kernel kernel = dev.kernel("pose_cluster.cl", "pose_compatibility");
  ocl::launch(dev, kernel, n, qb, tb, ab, vb, static_cast<std::uint32_t>(n), max_dist2(opt),
              min_cos_half(opt), sym.mode, gb, static_cast<std::uint32_t>(sym.rotations.size()),
              min_cos_axis(opt), compatible, scores);
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
  const ClusterSymmetry sym = cluster_symmetry(opt.symmetries);
  const std::vector<Eigen::Vector3f> axes = posed_axes(poses, sym);
  const std::vector<bp_quat> rotations = kernel_rotations(sym);
  const float d2 = max_dist2(opt), c = min_cos_half(opt), ca = min_cos_axis(opt);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      if (compatible(poses[i], poses[j], axes.empty() ? nullptr : &axes[i],
                     axes.empty() ? nullptr : &axes[j], rotations, sym.mode, d2, c, ca)) {
        out.compatible[i * n + j] = 1;
        out.scores[i] += poses[j].votes;
      }
  return out;
}

std::vector<PoseCluster> group_poses(const std::vector<PoseCandidate>& poses,
                                     const PoseCompatibility& m, const ClusterSymmetry& symmetry) {
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
      const Eigen::Quaterniond q = nearest_equivalent(poses[j].q.cast<double>(), qc, symmetry);
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
  std::vector<PoseCluster> clusters = group_poses(centred, m, cluster_symmetry(opt.symmetries));
  for (PoseCluster& c : clusters) c.t -= c.q * opt.centre.cast<double>();
  if (timings) timings->push_back({"cluster", clock.lap()});
  return clusters;
}

}  // namespace binpick
