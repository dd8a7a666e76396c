#include "host/detect/hypotheses/scene_cloud.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <Eigen/Eigenvalues>

#include "host/core/error.hpp"
#include "host/core/point_grid.hpp"
#include "kernels/scene_shared.h"

namespace binpick {
namespace {

void check_radius(float r, const char* what) {
  if (!(r > 0) || std::isinf(r)) throw InputError(std::string(what) + " must be positive (mm)");
}

}  // namespace

void check_cloud(const PointCloud& cloud) {
  if (!cloud.normals.empty() && cloud.normals.size() != cloud.points.size())
    throw InputError("cloud has " + std::to_string(cloud.normals.size()) + " normals for " +
                     std::to_string(cloud.points.size()) + " points");
  if (cloud.points.size() >= BP_NO_PIXEL) throw InputError("cloud too large");
  for (std::size_t i = 0; i < cloud.points.size(); ++i)
    if (!cloud.points[i].allFinite() || (!cloud.normals.empty() && !cloud.normals[i].allFinite()))
      throw InputError("cloud point " + std::to_string(i) + " has a NaN or infinite value");
}

std::vector<float> cloud_lowpass_z(const PointCloud& cloud, float radius, float max_jump) {
  check_cloud(cloud);
  check_radius(radius, "cloud low-pass radius");
  if (!(max_jump > 0)) throw InputError("cloud low-pass depth gate must be positive (mm)");
  const PointGrid grid(cloud, radius, 2);
  std::vector<float> out(cloud.points.size());
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    double sum = 0.0;
    int count = 0;
    const float zi = cloud.points[i].z();
    grid.near(cloud.points[i], radius, [&](std::uint32_t j) {
      if (std::fabs(cloud.points[j].z() - zi) <= max_jump) sum += cloud.points[j].z(), ++count;
    });
    out[i] = float(sum / count);  // count >= 1: the point itself
  }
  return out;
}

std::vector<Eigen::Vector3f> cloud_normals(const PointCloud& cloud, float radius) {
  check_cloud(cloud);
  check_radius(radius, "cloud normal radius");
  const PointGrid grid(cloud, radius, 3);
  std::vector<Eigen::Vector3f> out(cloud.points.size(), Eigen::Vector3f::Zero());
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const Eigen::Vector3d c = cloud.points[i].cast<double>();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d sq = Eigen::Matrix3d::Zero();
    int n = 0;
    grid.near(cloud.points[i], radius, [&](std::uint32_t j) {
      const Eigen::Vector3d q = cloud.points[j].cast<double>() - c;
      sum += q, sq += q * q.transpose(), ++n;
    });
    if (n < 3) continue;
    const Eigen::Vector3d mean = sum / n;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(sq / n - mean * mean.transpose());
    const Eigen::Vector3d ev = es.eigenvalues();
    if (!(ev[1] > double(BP_NORMAL_DEGENERATE_RATIO) * ev[2])) continue;
    Eigen::Vector3d nrm = es.eigenvectors().col(0).normalized();
    if (nrm.dot(c) > 0) nrm = -nrm;
    out[i] = nrm.cast<float>();
  }
  return out;
}

std::vector<Hypothesis> find_hypotheses(const PointCloud& cloud,
                                        const CloudHypothesisOptions& opt) {
  check(opt.hypotheses);
  const std::vector<float> filtered =
      cloud_lowpass_z(cloud, opt.lowpass_radius, opt.lowpass_max_jump);
  const std::size_t n = filtered.size();
  const float radius2 = opt.hypotheses.exclusion_radius * opt.hypotheses.exclusion_radius;
  std::vector<std::uint8_t> excluded(n, 0);
  std::vector<Hypothesis> out;
  for (std::uint32_t k = 0; k < opt.hypotheses.count; ++k) {
    float best = std::numeric_limits<float>::infinity();
    std::size_t best_i = n;
    for (std::size_t i = 0; i < n; ++i)
      if (!excluded[i] && filtered[i] < best) best = filtered[i], best_i = i;
    if (best_i == n) break;
    const Eigen::Vector3f h(cloud.points[best_i].x(), cloud.points[best_i].y(), best);
    out.push_back({std::uint32_t(best_i), 0, 0, best, h});
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3f& q = cloud.points[i];
      if (i == best_i || bp_dist2(q.x(), q.y(), q.z(), h.x(), h.y(), h.z()) <= radius2)
        excluded[i] = 1;
    }
  }
  return out;
}

PointCloud crop_sphere(const PointCloud& cloud, const CropOptions& opt) {
  check_cloud(cloud);
  if (!opt.centre.allFinite() || !(opt.radius >= 0) || std::isinf(opt.radius))
    throw InputError("crop centre and radius must be finite, the radius non-negative (mm)");
  if (opt.require_normals && cloud.normals.empty())
    throw InputError("cloud has no normals: estimate them first (cloud_normals)");
  const float r2 = opt.radius * opt.radius;
  const Eigen::Vector3f& c = opt.centre;
  PointCloud out;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    if (!(bp_dist2(p.x(), p.y(), p.z(), c.x(), c.y(), c.z()) <= r2)) continue;
    if (opt.require_normals && cloud.normals[i].isZero()) continue;
    out.points.push_back(p);
    if (!cloud.normals.empty()) out.normals.push_back(cloud.normals[i]);
  }
  return out;
}

}  // namespace binpick
