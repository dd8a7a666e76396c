#include "host/core/mesh_geometry.hpp"

#include <Eigen/Geometry>

namespace binpick {

BoundingBox bounding_box(const std::vector<Eigen::Vector3f>& points) {
  if (points.empty()) return {Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero()};
  BoundingBox box{points.front(), points.front()};
  for (const auto& p : points) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

double signed_volume(const Mesh& mesh) {
  double six_volume = 0;
  for (const auto& t : mesh.triangles) {
    Eigen::Vector3d a = mesh.positions[t[0]].cast<double>();
    Eigen::Vector3d b = mesh.positions[t[1]].cast<double>();
    Eigen::Vector3d c = mesh.positions[t[2]].cast<double>();
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6;
}

void scale_mesh(Mesh& mesh, double factor) {
  for (auto& p : mesh.positions) p = (p.cast<double>() * factor).cast<float>();
}

void translate_mesh(Mesh& mesh, const Eigen::Vector3f& offset) {
  for (auto& p : mesh.positions) p += offset;
}

}  // namespace binpick
