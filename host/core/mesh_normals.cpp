#include "host/core/mesh_normals.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <vector>

#include "host/core/mesh_topology.hpp"

namespace binpick {

void compute_crease_normals(Mesh& mesh, double crease_angle_degrees) {
  const double cos_crease = std::cos(crease_angle_degrees * std::numbers::pi / 180.0);
  // Face normals scaled by twice the area, and the faces around each vertex.
  std::vector<Eigen::Vector3d> area_normal(mesh.triangles.size());
  struct Corner {
    std::uint32_t face;
    std::uint32_t slot;  // 0, 1 or 2 within the face
  };
  std::vector<std::vector<Corner>> corners_of_vertex(mesh.positions.size());
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    const Eigen::Vector3d a = mesh.positions[t[0]].cast<double>();
    area_normal[f] =
        (mesh.positions[t[1]].cast<double>() - a).cross(mesh.positions[t[2]].cast<double>() - a);
    for (std::uint32_t slot = 0; slot < 3; ++slot) corners_of_vertex[t[slot]].push_back({f, slot});
  }
  auto unit_direction = [](const Eigen::Vector3d& n) {
    const double length = n.norm();
    return length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
  };

  auto smooth_across = [&](std::uint32_t f, std::uint32_t g) {
    return unit_direction(area_normal[f]).dot(unit_direction(area_normal[g])) >= cos_crease;
  };
  auto share_edge_at = [&](std::uint32_t v, std::uint32_t f, std::uint32_t g) {
    for (auto a : mesh.triangles[f]) {
      if (a == v) continue;
      for (auto b : mesh.triangles[g]) {
        if (a == b) return true;
      }
    }
    return false;
  };

  Mesh result;
  result.triangles = mesh.triangles;
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
    // The corners around v fall into smoothing groups: faces joined through shared edges that
    // are not sharper than the crease angle. Each group becomes one new vertex.
    const auto& corners = corners_of_vertex[v];
    std::vector<std::size_t> group(corners.size());
    for (std::size_t i = 0; i < corners.size(); ++i) group[i] = i;
    auto root = [&](std::size_t i) {
      while (group[i] != i) i = group[i] = group[group[i]];
      return i;
    };
    for (std::size_t i = 0; i < corners.size(); ++i) {
      for (std::size_t j = i + 1; j < corners.size(); ++j) {
        const auto f = corners[i].face, g = corners[j].face;
        if (share_edge_at(v, f, g) && smooth_across(f, g)) group[root(i)] = root(j);
      }
    }
    std::vector<Eigen::Vector3d> group_normal(corners.size(), Eigen::Vector3d::Zero());
    for (std::size_t i = 0; i < corners.size(); ++i)
      group_normal[root(i)] += area_normal[corners[i].face];
    std::vector<std::uint32_t> new_vertex(corners.size(), ~0u);
    for (std::size_t i = 0; i < corners.size(); ++i) {
      const std::size_t r = root(i);
      if (new_vertex[r] == ~0u) {
        new_vertex[r] = static_cast<std::uint32_t>(result.positions.size());
        result.positions.push_back(mesh.positions[v]);
        // A vertex only on zero-area faces has no defined normal; any unit vector will do.
        const Eigen::Vector3d n =
            group_normal[r].norm() > 0 ? unit_direction(group_normal[r]) : Eigen::Vector3d::UnitZ();
        result.normals.push_back(n.cast<float>());
      }
      result.triangles[corners[i].face][corners[i].slot] = new_vertex[r];
    }
  }
  mesh = std::move(result);
}

Mesh with_normals(const Mesh& mesh) {
  if (mesh.normals.size() == mesh.positions.size()) return mesh;
  Mesh copy{mesh.positions, {}, mesh.triangles};
  merge_duplicate_vertices(copy);
  compute_crease_normals(copy);
  return copy;
}

bool normalize_normals(Mesh& mesh) {
  for (auto& n : mesh.normals) {
    const float length = n.norm();
    if (!std::isfinite(length) || length == 0) return false;
    n /= length;
  }
  return true;
}

}  // namespace binpick
