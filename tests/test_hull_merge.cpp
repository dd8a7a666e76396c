// Merging HACD's hulls (synth/decompose/hull_merge.hpp): pieces of one convex solid become one
// hull; hulls whose merged hull would fill real concavities stay apart; the limits hold.
#include <gtest/gtest.h>

#include <LinearMath/btConvexHullComputer.h>

#include <Eigen/Geometry>

#include "host/mesh/load_model.hpp"
#include "synth/decompose/decompose.hpp"
#include "synth/decompose/hull_merge.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick {
namespace {

ConvexHull box_hull(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
  ConvexHull h;
  for (int i = 0; i < 8; ++i)
    h.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(),
                            i & 4 ? hi.z() : lo.z());
  return h;
}

// How far the mesh vertex farthest outside every hull lies outside (mm); 0 if all are inside.
double farthest_outside(const Mesh& mesh, const ConvexParts& parts) {
  std::vector<std::vector<Eigen::Vector4d>> planes;
  for (const auto& hull : parts.hulls) {
    std::vector<double> xyz;
    for (const auto& v : hull.vertices) xyz.insert(xyz.end(), {v.x(), v.y(), v.z()});
    btConvexHullComputer c;
    c.compute(xyz.data(), 3 * sizeof(double), static_cast<int>(hull.vertices.size()), 0, 0);
    auto& hp = planes.emplace_back();
    for (int f = 0; f < c.faces.size(); ++f) {
      const auto* first = &c.edges[c.faces[f]];
      const auto* e = first;
      std::vector<Eigen::Vector3d> poly;
      do {
        const btVector3& v = c.vertices[e->getSourceVertex()];
        poly.emplace_back(v.x(), v.y(), v.z());
        e = e->getNextEdgeOfFace();
      } while (e != first);
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      for (std::size_t i = 0; i < poly.size(); ++i) n += poly[i].cross(poly[(i + 1) % poly.size()]);
      n.normalize();
      hp.emplace_back(n.x(), n.y(), n.z(), -n.dot(poly[0]));
    }
  }
  double worst = 0;
  for (const auto& p : mesh.positions) {
    double best = INFINITY;
    for (const auto& hp : planes) {
      double out = -INFINITY;
      for (const auto& q : hp) out = std::max(out, q.head<3>().dot(p.cast<double>()) + q.w());
      best = std::min(best, out);
    }
    worst = std::max(worst, best);
  }
  return worst;
}

DecomposeOptions hacd_only() {
  DecomposeOptions o;
  o.use_cache = false;
  o.merge.max_added_per_merge = 0;
  return o;
}

TEST(HullMerge, UnionVolumeCountsOverlapsOnce) {
  ConvexParts one{{box_hull({0, 0, 0}, {10, 10, 10})}};
  EXPECT_NEAR(union_volume(one), 1000.0, 1e-6);
  ConvexParts overlapping{{box_hull({0, 0, 0}, {10, 10, 10}), box_hull({5, 0, 0}, {15, 10, 10})}};
  EXPECT_NEAR(union_volume(overlapping), 1500.0, 15.0);  // 1 % of grid resolution
  EXPECT_EQ(union_volume(ConvexParts{}), 0.0);
}

TEST(HullMerge, PiecesOfOneBoxBecomeOneHull) {
  ConvexParts pieces{{box_hull({0, 0, 0}, {10, 10, 10}), box_hull({10, 0, 0}, {20, 10, 10}),
                      box_hull({0, 10, 0}, {20, 15, 10})}};
  const ConvexParts merged = merge_hulls(pieces, {});
  ASSERT_EQ(merged.hulls.size(), 1u);
  EXPECT_EQ(merged.hulls[0].vertices.size(), 8u);  // only the extreme points are kept
  EXPECT_NEAR(union_volume(merged), 20 * 15 * 10, 1e-2);  // float vertices
}

TEST(HullMerge, HullsAroundARealConcavityStayApart) {
  // An L of two boxes: their hull would fill 50 % more volume.
  ConvexParts l{{box_hull({0, 0, 0}, {40, 5, 20}), box_hull({0, 5, 0}, {5, 30, 20})}};
  EXPECT_EQ(merge_hulls(l, {}).hulls.size(), 2u);
  // Two boxes far apart: never merged, whatever the limits.
  ConvexParts apart{{box_hull({0, 0, 0}, {10, 10, 10}), box_hull({100, 0, 0}, {110, 10, 10})}};
  EXPECT_EQ(merge_hulls(apart, {1.0, 1.0}).hulls.size(), 2u);
}

TEST(HullMerge, LimitsPerMergeAndInTotal) {
  // Two far-apart pairs of 10 mm cubes, each pair a step of 0.5 mm: merging a pair fills two
  // wedges of 25 mm^3, 50 mm^3 = 1.25 % of the 4000 mm^3 covered.
  ConvexParts steps;
  for (float x : {0.f, 100.f}) {
    steps.hulls.push_back(box_hull({x, 0, 0}, {x + 10, 10, 10}));
    steps.hulls.push_back(box_hull({x + 10, 0, 0.5f}, {x + 20, 10, 10.5f}));
  }
  EXPECT_EQ(merge_hulls(steps, {0.01, 1.0}).hulls.size(), 4u);   // 1.25 % > 1 % per merge
  EXPECT_EQ(merge_hulls(steps, {0.02, 1.0}).hulls.size(), 2u);   // each pair, never across
  EXPECT_EQ(merge_hulls(steps, {0.02, 0.03}).hulls.size(), 2u);  // 2.5 % in all
  EXPECT_EQ(merge_hulls(steps, {0.02, 0.02}).hulls.size(), 3u);  // the second would exceed 2 %
  EXPECT_EQ(merge_hulls(ConvexParts{{box_hull({0, 0, 0}, {1, 1, 1})}}, {}).hulls.size(), 1u);
  EXPECT_TRUE(merge_hulls(ConvexParts{}, {}).hulls.empty());
}

TEST(HullMerge, BuiltinBracketBecomesItsTwoPlatesAndStaysCovered) {
  const Mesh bracket = load_model("builtin:bracket", {});
  const ConvexParts hacd = decompose_convex(bracket, hacd_only());
  ASSERT_GT(hacd.hulls.size(), 4u) << "HACD no longer splits the bracket: the test lost its case";
  const ConvexParts merged = merge_hulls(hacd, {});
  EXPECT_EQ(merged.hulls.size(), 2u);
  EXPECT_LT(farthest_outside(bracket, merged), 0.01);  // merging only adds volume
  EXPECT_LE(union_volume(merged), 1.03 * union_volume(hacd));
  // The default decomposition merges.
  DecomposeOptions defaults;
  defaults.use_cache = false;
  EXPECT_EQ(decompose_convex(bracket, defaults).hulls.size(), 2u);
}

TEST(HullMerge, TorusKeepsItsHulls) {
  const ConvexParts hacd = decompose_convex(test::torus(), hacd_only());
  EXPECT_EQ(merge_hulls(hacd, {}).hulls.size(), hacd.hulls.size());
}

}  // namespace
}  // namespace binpick
