#include "host/core/mesh_refine.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "host/core/error.hpp"

namespace binpick {
namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;
Edge key(std::uint32_t a, std::uint32_t b) { return a < b ? Edge{a, b} : Edge{b, a}; }

// One pass: every edge longer than the limit gets its midpoint; each triangle is cut by the
// pattern of its split edges. Returns false when nothing was split.
bool split_pass(Mesh& m, double max_edge) {
  std::map<Edge, std::uint32_t> midpoint;
  const bool normals = m.normals.size() == m.positions.size();
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if ((m.positions[a] - m.positions[b]).norm() <= max_edge || midpoint.count(key(a, b))) continue;
      midpoint[key(a, b)] = std::uint32_t(m.positions.size());
      m.positions.push_back(0.5f * (m.positions[a] + m.positions[b]));
      if (normals) {
        const Eigen::Vector3f n = m.normals[a] + m.normals[b];
        m.normals.push_back(n.norm() > 1e-12f ? Eigen::Vector3f(n.normalized()) : m.normals[a]);
      }
    }
  if (midpoint.empty()) return false;
  std::vector<std::array<std::uint32_t, 3>> out;
  for (const auto& t : m.triangles) {
    std::array<int, 3> mid{-1, -1, -1};  // mid[k]: midpoint of edge t[k] -> t[k + 1]
    int splits = 0;
    for (int k = 0; k < 3; ++k)
      if (auto it = midpoint.find(key(t[k], t[(k + 1) % 3])); it != midpoint.end())
        mid[k] = int(it->second), ++splits;
    const auto M = [&](int k) { return std::uint32_t(mid[k]); };
    if (splits == 0) {
      out.push_back(t);
    } else if (splits == 3) {
      out.push_back({t[0], M(0), M(2)});
      out.push_back({M(0), t[1], M(1)});
      out.push_back({M(2), M(1), t[2]});
      out.push_back({M(0), M(1), M(2)});
    } else if (splits == 1) {
      const int k = int(std::find_if(mid.begin(), mid.end(), [](int v) { return v >= 0; }) - mid.begin());
      const std::uint32_t a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      out.push_back({a, M(k), c});
      out.push_back({M(k), b, c});
    } else {  // two: the unsplit edge is k, from a to b; c is opposite
      const int k = int(std::find(mid.begin(), mid.end(), -1) - mid.begin());
      const std::uint32_t a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      const std::uint32_t mbc = M((k + 1) % 3), mca = M((k + 2) % 3);
      out.push_back({mca, mbc, c});
      out.push_back({a, b, mbc});
      out.push_back({a, mbc, mca});
    }
  }
  m.triangles = std::move(out);
  return true;
}

}  // namespace

Mesh split_long_edges(const Mesh& mesh, double max_edge_mm) {
  if (!(max_edge_mm > 0)) throw InputError("edge length limit must be positive");
  for (const auto& t : mesh.triangles)
    for (std::uint32_t i : t)
      if (i >= mesh.positions.size()) throw InputError("mesh has a triangle index out of range");
  Mesh m = mesh;
  while (split_pass(m, max_edge_mm)) {
  }
  return m;
}

}  // namespace binpick
