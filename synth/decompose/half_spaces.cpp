#include "synth/decompose/half_spaces.hpp"

#include <LinearMath/btConvexHullComputer.h>

#include <Eigen/Geometry>
#include <limits>

namespace binpick {

HalfSpaces half_spaces(const std::vector<Eigen::Vector3f>& points) {
  std::vector<Eigen::Vector3d> in;
  in.reserve(points.size());
  for (const auto& p : points) in.push_back(p.cast<double>());
  btConvexHullComputer hull;
  hull.compute(in.data()->data(), sizeof(Eigen::Vector3d), static_cast<int>(in.size()), 0, 0);
  HalfSpaces h;
  h.lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  h.hi = -h.lo;
  for (int i = 0; i < hull.vertices.size(); ++i) {
    const btVector3& v = hull.vertices[i];
    const Eigen::Vector3d p(v.x(), v.y(), v.z());
    h.lo = h.lo.cwiseMin(p);
    h.hi = h.hi.cwiseMax(p);
    h.vertices.push_back(p.cast<float>());
  }
  for (int f = 0; f < hull.faces.size(); ++f) {
    // Newell's normal of the face polygon: robust for faces with many vertices.
    const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
    const btConvexHullComputer::Edge* e = first;
    std::vector<Eigen::Vector3d> polygon;
    do {
      const btVector3& v = hull.vertices[e->getSourceVertex()];
      polygon.emplace_back(v.x(), v.y(), v.z());
      e = e->getNextEdgeOfFace();
    } while (e != first);
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < polygon.size(); ++i)
      normal += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
    if (normal.norm() == 0.0) continue;
    normal.normalize();
    h.planes.emplace_back(normal.x(), normal.y(), normal.z(), -normal.dot(polygon.front()));
  }
  return h;
}

std::vector<HalfSpaces> half_spaces_of(const ConvexParts& parts) {
  std::vector<HalfSpaces> hulls;
  for (const auto& hull : parts.hulls) hulls.push_back(half_spaces(hull.vertices));
  return hulls;
}

bool contains(const HalfSpaces& hull, const Eigen::Vector3d& p) {
  if ((p.array() < hull.lo.array()).any() || (p.array() > hull.hi.array()).any()) return false;
  for (const auto& plane : hull.planes)
    if (plane.head<3>().dot(p) + plane.w() > 1e-9) return false;
  return true;
}

double outside_distance(const HalfSpaces& hull, const Eigen::Vector3d& p) {
  double out = -std::numeric_limits<double>::infinity();
  for (const auto& plane : hull.planes) out = std::max(out, plane.head<3>().dot(p) + plane.w());
  return out;
}

}  // namespace binpick
