// DecomposeOptions::max_hulls: a part HACD cuts into many pieces (the built-in bracket's holes)
// is decomposed again down to the limit, and the hulls still cover the part. (Parts under the
// limit are untouched by construction: the second run happens only above it.) The default
// cap counts the hulls after merging.
#include <gtest/gtest.h>

#include "host/app/options/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "synth/decompose/decompose.hpp"
#include "synth/decompose/hull_cover.hpp"

using namespace binpick;

namespace {

// Largest distance from a mesh vertex to the union of the hulls' bounding boxes: 0 when every
// vertex lies in some hull's box (a cheap necessary condition for covering the part).
float outside_all_boxes(const Mesh& mesh, const ConvexParts& parts) {
  float worst = 0;
  for (const auto& p : mesh.positions) {
    float best = std::numeric_limits<float>::max();
    for (const auto& h : parts.hulls) {
      Eigen::Vector3f lo = h.vertices.front(), hi = lo;
      for (const auto& v : h.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
      best = std::min(best, (p - p.cwiseMax(lo).cwiseMin(hi)).norm());
    }
    worst = std::max(worst, best);
  }
  return worst;
}

}  // namespace

TEST(DecomposeMaxHulls, a_part_with_holes_is_capped_and_still_covered) {
  const Mesh bracket = cli::load_part({"builtin:bracket", {}}).mesh;
  DecomposeOptions unlimited;
  unlimited.use_cache = false;
  unlimited.max_hulls = 0;
  unlimited.merge.max_added_per_merge = 0;  // HACD's own count (merging makes it 2)
  const ConvexParts many = decompose_convex(bracket, unlimited);
  ASSERT_GT(many.hulls.size(), 6u) << "the bracket's holes no longer split it: pick another part";

  // HACD takes seconds on this mesh: one cap only.
  DecomposeOptions capped;
  capped.use_cache = false;
  capped.max_hulls = 6;
  capped.merge.max_added_per_merge = 0;
  const ConvexParts few = decompose_convex(bracket, capped);
  EXPECT_LE(few.hulls.size(), capped.max_hulls);
  EXPECT_GE(few.hulls.size(), 1u);
  EXPECT_LT(outside_all_boxes(bracket, few), 0.5f);
  for (const auto& h : few.hulls) EXPECT_LE(h.vertices.size(), capped.max_hull_vertices);
}

// The default cap applies after merging: the built-in tee, which merging leaves at 15 hulls
// around its bore, comes out with at most max_hulls, and they still cover the mesh to the
// covering tolerance (hull_cover.hpp). The bracket, which merging brings to 2, keeps its 2.
TEST(DecomposeMaxHulls, the_default_caps_the_merged_tee_and_keeps_it_covered) {
  const Mesh tee = cli::load_part({"builtin:tee", {}}).mesh;
  DecomposeOptions uncapped;
  uncapped.use_cache = false;
  uncapped.max_hulls = 0;
  ASSERT_GT(decompose_convex(tee, uncapped).hulls.size(), DecomposeOptions{}.max_hulls)
      << "merging alone brings the tee under the cap: the test lost its case";

  DecomposeOptions defaults;
  defaults.use_cache = false;
  const ConvexParts capped = decompose_convex(tee, defaults);
  EXPECT_LE(capped.hulls.size(), defaults.max_hulls);
  EXPECT_GE(capped.hulls.size(), 2u);
  Eigen::Vector3f lo = tee.positions.front(), hi = lo;
  for (const auto& p : tee.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  EXPECT_LE(farthest_outside_mm(capped, tee), defaults.max_uncovered * (hi - lo).norm() + 1e-3);

  const Mesh bracket = cli::load_part({"builtin:bracket", {}}).mesh;
  EXPECT_EQ(decompose_convex(bracket, defaults).hulls.size(), 2u);
}
