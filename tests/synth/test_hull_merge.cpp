// Merging HACD's hulls (synth/decompose/hull_merge.hpp): pieces of one convex solid become one
// hull; hulls whose merged hull would fill real concavities stay apart; the limits hold. And
// growing them until they cover the mesh (hull_cover.hpp).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "host/app/options/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "synth/decompose/decompose.hpp"
#include "synth/decompose/hull_cover.hpp"
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

DecomposeOptions hacd_only() {
  DecomposeOptions o;
  o.use_cache = false;
  o.merge.max_added_per_merge = 0;
  o.max_uncovered = 0;
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
  const Mesh bracket = cli::load_part({"builtin:bracket", {}}).mesh;
  const ConvexParts hacd = decompose_convex(bracket, hacd_only());
  ASSERT_GT(hacd.hulls.size(), 4u) << "HACD no longer splits the bracket: the test lost its case";
  const ConvexParts merged = merge_hulls(hacd, {});
  EXPECT_EQ(merged.hulls.size(), 2u);
  EXPECT_LT(farthest_outside_mm(merged, bracket), 0.01);  // merging only adds volume
  EXPECT_LE(union_volume(merged), 1.03 * union_volume(hacd));
  // The default decomposition merges.
  DecomposeOptions defaults;
  defaults.use_cache = false;
  EXPECT_EQ(decompose_convex(bracket, defaults).hulls.size(), 2u);
}

// A sheet with holes becomes one slab, holes closed: as overlapping slabs, a plate lying on the
// plate was pushed sideways by their side faces inside the sheet (hull_merge.hpp).
TEST(HullMerge, BuiltinPlateBecomesOneSlab) {
  const Mesh plate = cli::load_part({"builtin:plate", {}}).mesh;
  const ConvexParts hacd = decompose_convex(plate, hacd_only());
  ASSERT_GT(hacd.hulls.size(), 4u) << "HACD no longer splits the plate: the test lost its case";
  const ConvexParts merged = merge_hulls(hacd, {});
  ASSERT_EQ(merged.hulls.size(), 1u);
  EXPECT_LT(thinnest_extent(merged.hulls[0]), 2.0);  // still the 1.5 mm sheet, not thickened
  EXPECT_LE(union_volume(merged), 1.05 * union_volume(hacd));
  EXPECT_LE(farthest_outside_mm(merged, plate), farthest_outside_mm(hacd, plate) + 1e-4);
}

TEST(HullMerge, TorusKeepsItsHulls) {
  const ConvexParts hacd = decompose_convex(test::torus(), hacd_only());
  EXPECT_EQ(merge_hulls(hacd, {}).hulls.size(), hacd.hulls.size());
}

TEST(HullCover, HullsGrowUntilTheMeshIsCovered) {
  const Mesh torus = test::torus();
  const ConvexParts hacd = decompose_convex(torus, hacd_only());
  ASSERT_GT(farthest_outside_mm(hacd, torus), 1.0) << "HACD's hulls cover the torus now: the "
                                                      "test lost its case";
  const ConvexParts covered = cover_mesh(hacd, torus, 0.3);
  EXPECT_LE(farthest_outside_mm(covered, torus), 0.3);
  ASSERT_EQ(covered.hulls.size(), hacd.hulls.size());
  for (const auto& hull : covered.hulls)  // grown, not rebuilt from the ~60 vertices of a segment
    EXPECT_LT(hull.vertices.size(), 48u);
  // The default decomposition covers it to 1 % of the diagonal: sqrt(52^2 + 52^2 + 12^2) mm.
  DecomposeOptions defaults;
  defaults.use_cache = false;
  EXPECT_LE(farthest_outside_mm(decompose_convex(torus, defaults), torus),
            0.01 * std::sqrt(52.0 * 52 * 2 + 12 * 12));
}

TEST(HullCover, CoveringHullsAreKeptAsTheyAre) {
  const Mesh l = test::l_bracket();
  const ConvexParts hacd = decompose_convex(l, hacd_only());
  EXPECT_LT(farthest_outside_mm(hacd, l), 1e-4);
  const ConvexParts covered = cover_mesh(hacd, l, 0.1);
  ASSERT_EQ(covered.hulls.size(), hacd.hulls.size());
  for (std::size_t h = 0; h < hacd.hulls.size(); ++h)
    EXPECT_EQ(covered.hulls[h].vertices.size(), hacd.hulls[h].vertices.size());
  EXPECT_TRUE(cover_mesh(ConvexParts{}, l, 0.1).hulls.empty());
  EXPECT_EQ(farthest_outside_mm(ConvexParts{}, Mesh{}), 0.0);
}

}  // namespace
}  // namespace binpick
