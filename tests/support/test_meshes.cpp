#include "tests/support/test_meshes.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace binpick::test {

Mesh l_bracket() {
  const std::vector<Eigen::Vector2f> outline = {{0, 0}, {40, 0}, {40, 5}, {5, 5}, {5, 30}, {0, 30}};
  const float width = 20;
  const auto n = static_cast<std::uint32_t>(outline.size());
  Mesh m;
  for (float z : {0.0f, width})
    for (const auto& p : outline) m.positions.emplace_back(p.x(), p.y(), z);
  // Fan from the reflex corner (index 3), which sees every other corner.
  for (std::uint32_t i : {4u, 5u, 0u, 1u}) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({3, j, i});              // bottom, facing -z
    m.triangles.push_back({n + 3, n + i, n + j});  // top, facing +z
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({i, j, n + j});
    m.triangles.push_back({i, n + j, n + i});
  }
  return m;
}

Mesh torus(int around, int across) {
  const int nu = around, nv = across;
  const double ring = 20, tube = 6;
  Mesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      m.positions.emplace_back(float((ring + tube * std::cos(v)) * std::cos(u)),
                               float((ring + tube * std::cos(v)) * std::sin(u)),
                               float(tube * std::sin(v)));
    }
  const auto at = [&](int i, int j) { return std::uint32_t((i % nu) * nv + j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

Mesh box(const Eigen::Vector3f& size) {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.emplace_back(i & 1 ? size.x() : 0.f, i & 2 ? size.y() : 0.f,
                             i & 4 ? size.z() : 0.f);
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

}  // namespace binpick::test
