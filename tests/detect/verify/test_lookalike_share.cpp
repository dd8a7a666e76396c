// The look-alike share (lookalike_share.hpp): a pose keeps s / (s + w a) of its score, a the
// best score among the poses of its own candidate turned another way round at its place.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "host/detect/verify/lookalike_share.hpp"

namespace binpick {
namespace {

VerifiedPose posed(double score, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  VerifiedPose r;
  r.breakdown[kAgreement] = score;  // every other factor neutral
  r.R = R;
  r.t = t;
  return r;
}

const Eigen::Vector3d kCentroid(5, -2, 1);  // off the origin: distances are between centroids
const Eigen::Matrix3d kTurnedOver =
    Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();

LookalikeOptions options() {
  LookalikeOptions o;
  o.max_distance = 12;
  return o;
}

// The turned pose at the same centroid: R' c + t' = R c + t.
VerifiedPose turned_at_same_place(double score, const VerifiedPose& of, const Eigen::Matrix3d& turn) {
  const Eigen::Matrix3d R = of.R * turn;
  return posed(score, R, of.R * kCentroid + of.t - R * kCentroid);
}

TEST(LookalikeShare, ATieHalvesBothScores) {
  std::vector<VerifiedPose> poses{posed(0.8, Eigen::Matrix3d::Identity(), {0, 0, 900})};
  poses.push_back(turned_at_same_place(0.8, poses[0], kTurnedOver));
  lookalike_share(poses, {0, 0}, kCentroid, options());
  EXPECT_NEAR(poses[0].score(), 0.4, 1e-12);
  EXPECT_NEAR(poses[1].score(), 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(poses[0].evidence.lookalike_score, 0.8);
  EXPECT_DOUBLE_EQ(poses[0].fit_score(), 0.8);  // the score before the share
}

TEST(LookalikeShare, EachShareIsTakenAgainstTheScoresBefore) {
  std::vector<VerifiedPose> poses{posed(0.6, Eigen::Matrix3d::Identity(), {10, 0, 800})};
  poses.push_back(turned_at_same_place(0.2, poses[0], kTurnedOver));
  lookalike_share(poses, {3, 3}, kCentroid, options());
  EXPECT_NEAR(poses[0].score(), 0.6 * 0.6 / 0.8, 1e-12);
  EXPECT_NEAR(poses[1].score(), 0.2 * 0.2 / 0.8, 1e-12);
  EXPECT_DOUBLE_EQ(poses[1].evidence.lookalike_score, 0.6);
  // Ranked by the shares, the pose that beats its look-alike stays first, further ahead.
  EXPECT_GT(poses[0].score() / poses[1].score(), 3.0);
}

TEST(LookalikeShare, TheBestLookalikeCountsAndTheWeightScalesIt) {
  std::vector<VerifiedPose> poses{posed(0.5, Eigen::Matrix3d::Identity(), {0, 0, 700})};
  poses.push_back(turned_at_same_place(0.1, poses[0], kTurnedOver));
  poses.push_back(turned_at_same_place(
      0.3, poses[0], Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
  LookalikeOptions o = options();
  o.weight = 0.5;
  lookalike_share(poses, {1, 1, 1}, kCentroid, o);
  EXPECT_DOUBLE_EQ(poses[0].evidence.lookalike_score, 0.3);
  EXPECT_NEAR(poses[0].score(), 0.5 * 0.5 / (0.5 + 0.5 * 0.3), 1e-12);
}

TEST(LookalikeShare, OtherPlacesTurnsCandidatesAndZeroScoresDoNotCount) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  std::vector<VerifiedPose> poses{posed(0.7, I, {0, 0, 900})};
  // Turned by 20 degrees only: the same pose refined a little differently, not a look-alike.
  const Eigen::Matrix3d small_turn =
      Eigen::AngleAxisd(20 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
  poses.push_back(turned_at_same_place(0.7, poses[0], small_turn));
  // Turned over, but 13 mm away: beyond max_distance.
  VerifiedPose away = turned_at_same_place(0.7, poses[0], kTurnedOver);
  away.t += Eigen::Vector3d(13, 0, 0);
  poses.push_back(away);
  // Turned over at the same place, but another candidate (another group).
  poses.push_back(turned_at_same_place(0.7, poses[0], kTurnedOver));
  // Turned over at the same place, same candidate, score 0: refined or verified to nothing.
  poses.push_back(turned_at_same_place(0.0, poses[0], kTurnedOver));
  lookalike_share(poses, {0, 0, 0, 1, 0}, kCentroid, options());
  EXPECT_DOUBLE_EQ(poses[0].score(), 0.7);
  EXPECT_DOUBLE_EQ(poses[0].evidence.lookalike_score, 0.0);
  EXPECT_DOUBLE_EQ(poses[4].score(), 0.0);  // a zero score stays zero, not NaN
  EXPECT_DOUBLE_EQ(poses[4].evidence.lookalike_score, 0.7);
}

TEST(LookalikeShare, WeightZeroIsOffAndMismatchedGroupsAreRefused) {
  std::vector<VerifiedPose> poses{posed(0.8, Eigen::Matrix3d::Identity(), {0, 0, 900})};
  poses.push_back(turned_at_same_place(0.8, poses[0], kTurnedOver));
  LookalikeOptions o = options();
  o.weight = 0;
  lookalike_share(poses, {0, 0}, kCentroid, o);
  EXPECT_DOUBLE_EQ(poses[0].score(), 0.8);
  EXPECT_DOUBLE_EQ(poses[1].score(), 0.8);
  EXPECT_DOUBLE_EQ(poses[1].fit_score(), 0.8);
  EXPECT_THROW(lookalike_share(poses, {0}, kCentroid, options()), std::logic_error);
  std::vector<VerifiedPose> none;
  EXPECT_NO_THROW(lookalike_share(none, {}, kCentroid, options()));
}

}  // namespace
}  // namespace binpick
