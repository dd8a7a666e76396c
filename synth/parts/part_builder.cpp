#include "synth/parts/part_builder.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "host/core/mesh_topology.hpp"

namespace binpick {

std::uint32_t PartBuilder::vertex(const Eigen::Vector3d& position, const Eigen::Vector3d& normal) {
  positions_.push_back(position);
  normals_.push_back(normal.normalized());
  return static_cast<std::uint32_t>(positions_.size() - 1);
}

void PartBuilder::triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const Eigen::Vector3d outward = normals_[a] + normals_[b] + normals_[c];
  const Eigen::Vector3d geometric =
      (positions_[b] - positions_[a]).cross(positions_[c] - positions_[a]);
  if (geometric.dot(outward) >= 0) {
    triangles_.push_back({a, b, c});
  } else {
    triangles_.push_back({a, c, b});
  }
}

void PartBuilder::quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  triangle(a, b, c);
  triangle(a, c, d);
}

void PartBuilder::convex_polygon(const std::vector<Eigen::Vector3d>& boundary,
                                 const Eigen::Vector3d& normal) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : boundary) centroid += p;
  centroid /= static_cast<double>(boundary.size());
  const std::uint32_t centre = vertex(centroid, normal);
  std::vector<std::uint32_t> ring;
  for (const auto& p : boundary) ring.push_back(vertex(p, normal));
  for (std::size_t i = 0; i < ring.size(); ++i)
    triangle(centre, ring[i], ring[(i + 1) % ring.size()]);
}

Mesh PartBuilder::build() const {
  Mesh mesh;
  for (const auto& p : positions_) mesh.positions.push_back(p.cast<float>());
  for (const auto& n : normals_) mesh.normals.push_back(n.cast<float>());
  mesh.triangles = triangles_;
  merge_duplicate_vertices(mesh);
  return mesh;
}

Eigen::Vector2d unit_circle_point(int i, int n) {
  i = ((i % n) + n) % n;
  if (4 * i % n == 0) {
    switch (4 * i / n) {
      case 0:
        return {1, 0};
      case 1:
        return {0, 1};
      case 2:
        return {-1, 0};
      default:
        return {0, -1};
    }
  }
  const double angle = 2 * std::numbers::pi * i / n;
  return {std::cos(angle), std::sin(angle)};
}

Eigen::Vector3d ring_point(int i, int n, double radius, double z) {
  const Eigen::Vector2d d = unit_circle_point(i, n);
  return {radius * d.x(), radius * d.y(), z};
}

void add_surface_of_revolution(PartBuilder& b, int n, double r0, double z0, double r1, double z1) {
  // Outward normal of the profile segment from (r0, z0) to (r1, z1), rotated to each sample.
  const Eigen::Vector2d profile_normal = Eigen::Vector2d(z1 - z0, r0 - r1).normalized();
  for (int i = 0; i < n; ++i) {
    auto normal_at = [&](int k) {
      const Eigen::Vector2d d = unit_circle_point(k, n);
      return Eigen::Vector3d(profile_normal.x() * d.x(), profile_normal.x() * d.y(),
                             profile_normal.y());
    };
    b.quad(b.vertex(ring_point(i, n, r0, z0), normal_at(i)),
           b.vertex(ring_point(i + 1, n, r0, z0), normal_at(i + 1)),
           b.vertex(ring_point(i + 1, n, r1, z1), normal_at(i + 1)),
           b.vertex(ring_point(i, n, r1, z1), normal_at(i)));
  }
}

}  // namespace binpick
