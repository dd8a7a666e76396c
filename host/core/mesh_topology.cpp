#include "host/core/mesh_topology.hpp"

#include <Eigen/Geometry>
#include <map>
#include <unordered_map>
#include <utility>

namespace binpick {
namespace {

// Hashable exact key of a float vector; adding 0.0f maps -0 to +0 so they weld.
struct FloatKey {
  std::vector<float> values;
  bool operator==(const FloatKey&) const = default;
};
struct FloatKeyHash {
  std::size_t operator()(const FloatKey& key) const {
    std::size_t h = 1469598103934665603ull;
    for (float v : key.values) h = (h ^ std::hash<float>{}(v + 0.0f)) * 1099511628211ull;
    return h;
  }
};

FloatKey key_of(const Eigen::Vector3f& p) { return {{p.x() + 0.0f, p.y() + 0.0f, p.z() + 0.0f}}; }

}  // namespace

std::vector<std::uint32_t> first_index_at_same_position(
    const std::vector<Eigen::Vector3f>& points) {
  std::unordered_map<FloatKey, std::uint32_t, FloatKeyHash> first;
  first.reserve(points.size());
  std::vector<std::uint32_t> result(points.size());
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    result[i] = first.emplace(key_of(points[i]), i).first->second;
  }
  return result;
}

void merge_duplicate_vertices(Mesh& mesh) {
  const bool with_normals = mesh.normals.size() == mesh.positions.size();
  std::unordered_map<FloatKey, std::uint32_t, FloatKeyHash> index_of;
  std::vector<std::uint32_t> new_index(mesh.positions.size());
  Mesh merged;
  for (std::uint32_t i = 0; i < mesh.positions.size(); ++i) {
    FloatKey key = key_of(mesh.positions[i]);
    if (with_normals) {
      FloatKey n = key_of(mesh.normals[i]);
      key.values.insert(key.values.end(), n.values.begin(), n.values.end());
    }
    auto [it, inserted] = index_of.emplace(std::move(key), merged.positions.size());
    if (inserted) {
      merged.positions.push_back(mesh.positions[i]);
      if (with_normals) merged.normals.push_back(mesh.normals[i]);
    }
    new_index[i] = it->second;
  }
  for (auto& t : mesh.triangles) {
    for (auto& v : t) v = new_index[v];
  }
  mesh.positions = std::move(merged.positions);
  mesh.normals = std::move(merged.normals);
}

void remove_collapsed_triangles(Mesh& mesh) {
  std::erase_if(mesh.triangles,
                [](const auto& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; });
}

void remove_unreferenced_vertices(Mesh& mesh) {
  constexpr std::uint32_t unused = ~0u;
  std::vector<std::uint32_t> new_index(mesh.positions.size(), unused);
  const bool with_normals = mesh.normals.size() == mesh.positions.size();
  Mesh kept;
  for (auto& t : mesh.triangles) {
    for (auto& v : t) {
      if (new_index[v] == unused) {
        new_index[v] = kept.positions.size();
        kept.positions.push_back(mesh.positions[v]);
        if (with_normals) kept.normals.push_back(mesh.normals[v]);
      }
      v = new_index[v];
    }
  }
  mesh.positions = std::move(kept.positions);
  mesh.normals = std::move(kept.normals);
}

TopologyReport check_topology(const Mesh& mesh) {
  const auto weld = first_index_at_same_position(mesh.positions);
  TopologyReport report;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed_uses;
  for (const auto& t : mesh.triangles) {
    const std::uint32_t a = weld[t[0]], b = weld[t[1]], c = weld[t[2]];
    const Eigen::Vector3d pa = mesh.positions[a].cast<double>();
    const double area2 =
        (mesh.positions[b].cast<double>() - pa).cross(mesh.positions[c].cast<double>() - pa).norm();
    if (a == b || b == c || c == a || area2 == 0) {
      ++report.degenerate_triangles;
      continue;
    }
    ++directed_uses[{a, b}];
    ++directed_uses[{b, c}];
    ++directed_uses[{c, a}];
  }
  for (const auto& [edge, forward] : directed_uses) {
    const auto [u, v] = edge;
    auto reverse_it = directed_uses.find({v, u});
    const int backward = reverse_it == directed_uses.end() ? 0 : reverse_it->second;
    if (u > v && backward > 0) continue;  // counted from the (v, u) side
    if (forward + backward > 2) {
      ++report.non_manifold_edges;
    } else if (forward == 2 || backward == 2) {
      ++report.misoriented_edges;
    } else if (backward == 0) {
      ++report.boundary_edges;
    }
  }
  return report;
}

}  // namespace binpick
