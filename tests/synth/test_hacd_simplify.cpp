// The mesh HACD sees: a CAD export of many triangles is simplified first, keeping its topology,
// and the hulls made from it still cover the mesh itself.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

#include "synth/decompose/decompose.hpp"
#include "synth/decompose/hacd_simplify.hpp"
#include "synth/decompose/hull_cover.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick {
namespace {

// The mesh as HACD takes it.
HacdMesh to_hacd(const Mesh& m) {
  HacdMesh h;
  for (const auto& p : m.positions) h.points.push_back(p.cast<double>());
  for (const auto& t : m.triangles) h.triangles.push_back({long(t[0]), long(t[1]), long(t[2])});
  return h;
}

// Each undirected edge with the number of triangles using it.
std::map<std::pair<long, long>, int> edge_uses(const HacdMesh& m) {
  std::map<std::pair<long, long>, int> uses;
  for (const auto& t : m.triangles)
    for (int c = 0; c < 3; ++c) {
      const long a = t[c], b = t[(c + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  return uses;
}

TEST(HacdSimplify, AMeshWithinTheLimitIsUnchanged) {
  const HacdMesh torus = to_hacd(test::torus());
  const HacdMesh same = simplify_for_hacd(torus, torus.triangles.size(), 10);
  EXPECT_EQ(same.points, torus.points);
  EXPECT_EQ(same.triangles, torus.triangles);
}

TEST(HacdSimplify, ADenseTorusStaysAClosedTorusOfAtMostTheTarget) {
  const HacdMesh dense = to_hacd(test::torus(160, 60));  // 19200 triangles
  const HacdMesh simple = simplify_for_hacd(dense, 1500, 1000);
  ASSERT_GE(simple.triangles.size(), 100u);
  EXPECT_LE(simple.triangles.size(), 1000u);
  // Closed (every edge between two triangles) and still of genus one: V - E + F = 0.
  const auto uses = edge_uses(simple);
  for (const auto& [edge, n] : uses) EXPECT_EQ(n, 2) << edge.first << "-" << edge.second;
  EXPECT_EQ(long(simple.points.size()) - long(uses.size()) + long(simple.triangles.size()), 0);
  // Its points are the mesh's own: on the torus's surface.
  for (const auto& p : simple.points) {
    const double ring = std::hypot(p.x(), p.y()) - 20;
    EXPECT_NEAR(std::hypot(ring, p.z()), 6.0, 1e-4);
  }
  // Deterministic.
  const HacdMesh again = simplify_for_hacd(dense, 1500, 1000);
  EXPECT_EQ(again.points, simple.points);
  EXPECT_EQ(again.triangles, simple.triangles);
}

TEST(HacdSimplify, ATargetOfZeroOrAboveTheLimitIsRefused) {
  const HacdMesh torus = to_hacd(test::torus());
  EXPECT_THROW(simplify_for_hacd(torus, 100, 0), std::invalid_argument);
  EXPECT_THROW(simplify_for_hacd(torus, 100, 101), std::invalid_argument);
}

TEST(HacdSimplify, HullsOfASimplifiedMeshCoverTheMeshItself) {
  const Mesh dense = test::torus(160, 60);
  DecomposeOptions options;
  options.use_cache = false;
  const ConvexParts parts = decompose_convex(dense, options);
  ASSERT_GE(parts.hulls.size(), 2u);  // the hole is still a hole
  const double diagonal = std::sqrt(52.0 * 52.0 * 2 + 12.0 * 12.0);
  EXPECT_LE(farthest_outside_mm(parts, dense), options.max_uncovered * diagonal + 1e-3);
}

}  // namespace
}  // namespace binpick
