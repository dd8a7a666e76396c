// DecomposeOptions::max_hulls: a part HACD cuts into many pieces (the built-in bracket's holes)
// is decomposed again down to the limit, and the hulls still cover the part. (Parts under the
// limit are untouched by construction: the second run happens only above it.)
#include <gtest/gtest.h>

#include "host/app/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "synth/decompose/decompose.hpp"

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
