#include "host/train/ppf_features.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Geometry>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/core/error.hpp"
#include "host/core/cloud_input.hpp"

namespace binpick {

bp_ppf_quant make_ppf_quant(float max_distance, std::uint32_t distance_steps,
                            std::uint32_t angle_steps) {
  if (!(max_distance > 0 && std::isfinite(max_distance)))
    throw InputError("PPF maximum distance (the diameter) " + std::to_string(max_distance) +
                     " must be positive and finite");
  if (distance_steps < 1 || distance_steps > 1000)
    throw InputError("distance steps " + std::to_string(distance_steps) +
                     " must be in [1, 1000] (the paper uses 20)");
  if (angle_steps < 4 || angle_steps > 360)
    throw InputError("angle steps " + std::to_string(angle_steps) +
                     " must be in [4, 360] (the paper uses 30, i.e. 12 degrees)");
  bp_ppf_quant q{};
  q.max_distance = max_distance;
  q.n_dist = distance_steps;
  q.dist_step = max_distance / float(distance_steps);
  q.n_alpha = angle_steps;
  q.angle_step = float(2 * std::numbers::pi / angle_steps);
  q.n_angle = (angle_steps + 1) / 2;  // bins of [0, pi]
  if (std::uint64_t(q.n_dist) * q.n_angle * q.n_angle * q.n_angle > (1u << 24))
    throw InputError("distance steps " + std::to_string(distance_steps) + " and angle steps " +
                     std::to_string(angle_steps) + " give more than 2^24 feature keys");
  return q;
}

PointCloud ppf_input(const PointCloud& cloud, std::size_t max_points, const char* what) {
  check_point_cloud(cloud, true, what);
  if (cloud.points.size() > max_points)
    throw InputError(std::string(what) + ": " + std::to_string(cloud.points.size()) +
                     " points, at most " + std::to_string(max_points) + " are supported");
  return with_unit_normals(cloud);
}

PairFeatures ppf_pair_features(ocl::Device& dev, const PointCloud& input, const bp_ppf_quant& quant) {
  const PointCloud cloud = ppf_input(input, 8192, "point pair features");
  const std::size_t n = cloud.points.size();
  ocl::Buffer<cl_float4> points(dev, std::span<const cl_float4>(pack_float4(cloud.points)),
                                CL_MEM_READ_ONLY);
  ocl::Buffer<cl_float4> normals(dev, std::span<const cl_float4>(pack_float4(cloud.normals)),
                                 CL_MEM_READ_ONLY);
  ocl::Buffer<std::uint32_t> keys(dev, n * n, CL_MEM_WRITE_ONLY);
  ocl::Buffer<float> alphas(dev, n * n, CL_MEM_WRITE_ONLY);
  cl::Kernel k = dev.kernel("ppf_features.cl", "ppf_pair_features");
  ocl::launch(dev, k, n, points, normals, static_cast<std::uint32_t>(n), quant, keys, alphas);
  return {n, keys.read(dev), alphas.read(dev)};
}

namespace {

float angle_between(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

float ppf_alpha_reference(const Eigen::Vector3f& nr, const Eigen::Vector3f& d) {
  const Eigen::Vector3f x = Eigen::Vector3f::UnitX();
  Eigen::Matrix3f r;
  const Eigen::Vector3f axis = nr.cross(x);
  if (axis.squaredNorm() > BP_PPF_AXIS_SIN2)
    r = Eigen::AngleAxisf(std::atan2(axis.norm(), nr.dot(x)), axis.normalized()).toRotationMatrix();
  else if (nr.x() > 0)
    r.setIdentity();
  else
    r = Eigen::AngleAxisf(float(std::numbers::pi), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  const Eigen::Vector3f rd = r * d;
  const float lim = BP_PPF_AXIS_RATIO * d.norm();
  if (rd.y() * rd.y() + rd.z() * rd.z() <= lim * lim) return 0.0f;
  return bp_ppf_wrap_alpha(std::atan2(rd.z(), rd.y()));
}

PairFeature ppf_pair_feature_reference(const Eigen::Vector3f& pr, const Eigen::Vector3f& nr,
                                       const Eigen::Vector3f& pi, const Eigen::Vector3f& ni,
                                       const bp_ppf_quant& q) {
  PairFeature out;
  const Eigen::Vector3f d = pi - pr;
  const float dist = d.norm();
  out.f[0] = dist;
  if (!(dist <= q.max_distance) || dist <= BP_PPF_MIN_DIST_RATIO * q.max_distance) return out;
  out.valid = true;
  out.f[1] = angle_between(nr, d);
  out.f[2] = angle_between(ni, d);
  out.f[3] = angle_between(nr, ni);
  out.alpha = ppf_alpha_reference(nr, d);
  out.key = bp_ppf_feature_key(out.f[0], out.f[1], out.f[2], out.f[3], q);
  return out;
}

PairFeatures ppf_pair_features_reference(const PointCloud& input, const bp_ppf_quant& quant) {
  const PointCloud cloud = ppf_input(input, 8192, "point pair features");
  const std::size_t n = cloud.points.size();
  PairFeatures out{n, std::vector<std::uint32_t>(n * n, BP_PPF_NO_KEY),
                   std::vector<float>(n * n, 0.0f)};
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t i = 0; i < n; ++i) {
      if (i == r) continue;
      const PairFeature f = ppf_pair_feature_reference(cloud.points[r], cloud.normals[r],
                                                       cloud.points[i], cloud.normals[i], quant);
      out.keys[r * n + i] = f.key;
      out.alphas[r * n + i] = f.alpha;
    }
  return out;
}

}  // namespace binpick
