// The coarse ranking of the highest points (--prerank; host/detect/hypotheses/prerank.hpp): the
// order on given votes, and a detection where the highest point lies on another part.
#include <gtest/gtest.h>

#include <stdexcept>

#include "host/app/model_options.hpp"
#include "host/detect/detector.hpp"
#include "host/detect/hypotheses/prerank.hpp"
#include "host/eval/metrics/pose_error.hpp"
#include "host/train/ppf_model.hpp"
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
  const Model part = cli::load_part({"builtin:shaft", {}});
  const PpfModel model = train_ppf_model(part.mesh, {});
  Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
  T.linear() = Eigen::AngleAxisf(0.3f, Eigen::Vector3f(0.2f, 0.5f, 0.8f).normalized())
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3f(-60, 10, 600);
  Eigen::Isometry3f S = Eigen::Isometry3f::Identity();
  S.linear() = Eigen::AngleAxisf(0.4f, Eigen::Vector3f::UnitX()).toRotationMatrix();
  S.translation() = Eigen::Vector3f(55, -20, 560);
  const test::RenderedScene scene =
      test::render_parts({{part.mesh, T}, {test::torus(), S}}, 600.0f + model.diameter);
  for (int path = 0; path < 2; ++path) {
    SCOPED_TRACE(path == 0 ? "depth image" : "cloud");
    for (const bool prerank : {false, true}) {
      SCOPED_TRACE(prerank ? "ranked" : "height order");
      DetectParams p;
      p.hypotheses = 1;
      p.more_hypotheses = 1;
      p.confident = 0;  // no second round
      p.prerank = prerank;
      Detector detector(model, p);
      const auto found =
          path == 0 ? detector.detect(scene.depth, scene.cam) : detector.detect(scene.cloud);
      ASSERT_EQ(found.size(), 1u);
      const eval::PoseError e =
          eval::symmetric_pose_error(T.linear().cast<double>(), T.translation().cast<double>(),
                                     found[0].R, found[0].t, part.symmetries);
      if (prerank) {
        EXPECT_LT(e.translation_mm, 0.05 * model.diameter);
        EXPECT_LT(e.rotation_deg, 5.0);
        EXPECT_EQ(found[0].index, 1u);  // the second highest point
      } else {
        EXPECT_GT(e.translation_mm, 0.5 * model.diameter);  // on the torus
        EXPECT_EQ(found[0].index, 0u);
      }
    }
  }
}
