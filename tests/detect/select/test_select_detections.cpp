// From verified poses to detections (select/select_detections.hpp): each hypothesis' best pose,
// ties to the first (the more voted candidate), hypotheses without a pose dropped, ranked by
// score, then votes, then height order.
#include <gtest/gtest.h>

#include "host/detect/select/select_detections.hpp"

namespace binpick {
namespace {

VerifiedPose verified(double score, double x) {
  VerifiedPose v;
  v.breakdown[kAgreement] = score;
  v.t = Eigen::Vector3d(x, 0, 500);
  return v;
}

TEST(SelectDetections, EachHypothesisKeepsItsBestAndTheyRankByScore) {
  std::vector<Detection> hypotheses(4);
  for (std::uint32_t k = 0; k < 4; ++k) hypotheses[k].index = k;
  // Hypothesis 0: two candidates tie (the first, more voted, stays); 1: none; 2: a look-alike
  // wins; 3: ties hypothesis 0's score with fewer votes.
  const std::vector<VerifiedPose> poses = {verified(0.6, 1), verified(0.6, 2), verified(0.3, 3),
                                           verified(0.8, 4), verified(0.6, 5)};
  const std::vector<PoseOrigin> origin = {
      {0, 0, 0, 50}, {0, 1, 0, 20}, {2, 0, 0, 30}, {2, 0, 1, 30}, {3, 0, 0, 10}};
  const auto out = best_per_hypothesis(hypotheses, poses, origin);
  ASSERT_EQ(out.size(), 3u);  // hypothesis 1 got no pose
  EXPECT_EQ(out[0].index, 2u);
  EXPECT_EQ(out[0].lookalike, 1u);
  EXPECT_DOUBLE_EQ(out[0].score(), 0.8);
  EXPECT_EQ(out[1].index, 0u);
  EXPECT_EQ(out[1].t.x(), 1.0);  // the tie went to the first candidate
  EXPECT_EQ(out[1].votes, 50u);
  EXPECT_EQ(out[2].index, 3u);  // the same score, fewer votes
  EXPECT_TRUE(ranks_before(out[1], out[2]));
  EXPECT_FALSE(ranks_before(out[2], out[1]));

  const auto all = every_pose(hypotheses, poses, origin);
  ASSERT_EQ(all.size(), poses.size());
  EXPECT_EQ(all[3].index, 2u);
  EXPECT_EQ(all[3].candidate, 0u);
  EXPECT_EQ(all[1].candidate, 1u);
  EXPECT_TRUE(best_per_hypothesis(hypotheses, {}, {}).empty());
}

}  // namespace
}  // namespace binpick
