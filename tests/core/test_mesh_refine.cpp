// split_long_edges (BOP's models_eval/): no edge above the limit, the same surface (area,
// bounding box, closed and consistently wound), new vertices on the old edges.
#include <gtest/gtest.h>

#include <map>

#include <Eigen/Geometry>

#include "host/core/error.hpp"
#include "host/core/mesh_refine.hpp"
#include "tests/support/test_meshes.hpp"

using namespace binpick;

namespace {

double area(const Mesh& m) {
  double a = 0;
  for (const auto& t : m.triangles)
    a += 0.5 * double((m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).norm());
  return a;
}

Eigen::Vector3d signed_volume_and_check(const Mesh& m) {
  // Closed and consistently wound: every directed edge appears once and its reverse once.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  double volume = 0;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    volume += double(m.positions[t[0]].dot(m.positions[t[1]].cross(m.positions[t[2]]))) / 6.0;
  }
  int bad = 0;
  for (const auto& [e, n] : directed) bad += n != 1 || !directed.count({e.second, e.first});
  return {volume, double(bad), 0};
}

}  // namespace

TEST(SplitLongEdges, NoLongEdgeAndTheSameClosedSurface) {
  const Mesh bracket = test::l_bracket();
  const Mesh fine = split_long_edges(bracket, 1.3);
  EXPECT_GT(fine.positions.size(), 20 * bracket.positions.size());
  for (const auto& t : fine.triangles)
    for (int k = 0; k < 3; ++k)
      ASSERT_LE((fine.positions[t[k]] - fine.positions[t[(k + 1) % 3]]).norm(), 1.3f);
  EXPECT_NEAR(area(fine), area(bracket), 1e-3 * area(bracket));
  const Eigen::Vector3d before = signed_volume_and_check(bracket), after = signed_volume_and_check(fine);
  EXPECT_EQ(before[1], 0);
  EXPECT_EQ(after[1], 0);  // no T-junction, no flipped triangle
  EXPECT_NEAR(after[0], before[0], 1e-3 * std::abs(before[0]));
  for (int a = 0; a < 3; ++a) {
    float lo0 = 1e9f, hi0 = -1e9f, lo1 = 1e9f, hi1 = -1e9f;
    for (const auto& p : bracket.positions) lo0 = std::min(lo0, p[a]), hi0 = std::max(hi0, p[a]);
    for (const auto& p : fine.positions) lo1 = std::min(lo1, p[a]), hi1 = std::max(hi1, p[a]);
    EXPECT_EQ(lo0, lo1);
    EXPECT_EQ(hi0, hi1);
  }
}

TEST(SplitLongEdges, ShortEdgesAreKeptAndNormalsFollow) {
  Mesh torus = test::torus();
  const Mesh same = split_long_edges(torus, 1000.0);
  EXPECT_EQ(same.positions.size(), torus.positions.size());
  EXPECT_EQ(same.triangles, torus.triangles);
  torus.normals.assign(torus.positions.size(), Eigen::Vector3f::UnitZ());
  const Mesh fine = split_long_edges(torus, 1.0);
  ASSERT_EQ(fine.normals.size(), fine.positions.size());
  for (const auto& n : fine.normals) EXPECT_NEAR(n.z(), 1.0f, 1e-6f);
}

TEST(SplitLongEdges, BadInputIsAnInputError) {
  EXPECT_THROW(split_long_edges(test::torus(), 0.0), InputError);
  Mesh broken = test::torus();
  broken.triangles.push_back({0, 1, 999999});
  EXPECT_THROW(split_long_edges(broken, 1.0), InputError);
}
