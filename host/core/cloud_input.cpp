#include "host/core/cloud_input.hpp"

#include <string>

#include "host/core/error.hpp"

namespace binpick {

void check_point_cloud(const PointCloud& cloud, bool need_normals, std::string_view what) {
  const std::string prefix(what);
  for (std::size_t i = 0; i < cloud.points.size(); ++i)
    if (!cloud.points[i].allFinite())
      throw InputError(prefix + ": point " + std::to_string(i) + " is not finite (NaN or inf)");
  if (!need_normals && cloud.normals.empty()) return;
  if (cloud.normals.size() != cloud.points.size())
    throw InputError(prefix + ": " + std::to_string(cloud.normals.size()) + " normals for " +
                     std::to_string(cloud.points.size()) + " points");
  for (std::size_t i = 0; i < cloud.normals.size(); ++i) {
    const Eigen::Vector3f& n = cloud.normals[i];
    if (!n.allFinite() || !(n.squaredNorm() > 1e-20f))
      throw InputError(prefix + ": normal " + std::to_string(i) + " is zero or not finite");
  }
}

PointCloud with_unit_normals(const PointCloud& cloud) {
  PointCloud out = cloud;
  for (auto& n : out.normals) n.normalize();
  return out;
}

std::vector<cl_float4> pack_float4(const std::vector<Eigen::Vector3f>& v) {
  std::vector<cl_float4> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = {{v[i].x(), v[i].y(), v[i].z(), 0.0f}};
  return out;
}

}  // namespace binpick
