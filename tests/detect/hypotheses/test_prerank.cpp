// The coarse ranking of the highest points (--prerank; host/detect/hypotheses/prerank.hpp): the
// order on given votes, and a detection where the highest point lies on another part.
#include <gtest/gtest.h>

#include <stdexcept>

#include "host/detect/detector.hpp"
#include "host/detect/hypotheses/prerank.hpp"
#include "tests/support/rendered_parts.hpp"
#include "tests/support/test_meshes.hpp"

using namespace binpick;

// Most votes first, ties in height order, points not voted on (votes < 0) after those voted
// on; the points beyond the ranked ones follow in height order.
TEST(Prerank, OrderIsByVotesThenHeight) {
  using V = std::vector<std::size_t>;
  EXPECT_EQ(prerank_order({3, -1, 7, 3, 0}, 7), (V{2, 0, 3, 4, 1, 5, 6}));
  EXPECT_EQ(prerank_order({}, 3), (V{0, 1, 2}));
  EXPECT_EQ(prerank_order({}, 0), V{});
  EXPECT_EQ(prerank_order({-1, -1}, 2), (V{0, 1}));
  EXPECT_THROW(prerank_order({1, 2, 3}, 2), std::logic_error);
}

// A torus lies 40 mm nearer the camera than a shaft of the same diameter, beside it: the
// highest point is on the torus. Of the two highest points sought, the first round takes one:
// in height order the torus (a pose far from the shaft), ranked by the coarse vote the shaft.
// On the depth image and on the cloud alike.
TEST(Prerank, TheHighestPointOnAnotherPartIsVotedAfterThePartSought) {
  Eigen::Isometry3f S = Eigen::Isometry3f::Identity();
  S.linear() = Eigen::AngleAxisf(0.4f, Eigen::Vector3f::UnitX()).toRotationMatrix();
  S.translation() = Eigen::Vector3f(55, -20, 560);
  const test::ShaftBeside shaft = test::shaft_beside({-60, 10, 600}, test::torus(), S);
  const test::RenderedScene& scene = shaft.scene;
  for (int path = 0; path < 2; ++path) {
    SCOPED_TRACE(path == 0 ? "depth image" : "cloud");
    for (const bool prerank : {false, true}) {
      SCOPED_TRACE(prerank ? "ranked" : "height order");
      DetectParams p;
      p.hypotheses = 1;
      p.more_hypotheses = 1;
      p.confident = 0;  // no second round
      p.prerank = prerank;
      Detector detector(shaft.model, p);
      const auto found =
          path == 0 ? detector.detect(scene.depth, scene.cam) : detector.detect(scene.cloud);
      ASSERT_EQ(found.size(), 1u);
      const eval::PoseError e = shaft.error_of(found[0]);
      if (prerank) {
        EXPECT_LT(e.translation_mm, 0.05 * shaft.model.diameter);
        EXPECT_LT(e.rotation_deg, 5.0);
        EXPECT_EQ(found[0].index, 1u);  // the second highest point
      } else {
        EXPECT_GT(e.translation_mm, 0.5 * shaft.model.diameter);  // on the torus
        EXPECT_EQ(found[0].index, 0u);
      }
    }
  }
}
