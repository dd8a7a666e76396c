// What detection returns for one pose: the pose, its verified score and what the score is made
// of, the votes, and where it came from (hypothesis, candidate, look-alike).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "host/detect/hypotheses/hypotheses.hpp"
#include "host/detect/verify/verified_pose.hpp"

namespace binpick {

// A detection's pick (host/detect/pick/plan_picks.hpp): the grasp a robot should use and where
// it is, or why the detection gives none.
struct PlannedPick {
  bool picked = false;
  std::size_t grasp = 0;          // index into the grasps
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // the grasp's frame, camera frame
  double width = 0;               // mm: the grasp's cup diameter or jaws' opening
  double clearance = 0;           // mm, up to a quarter of the diameter
  double value = 0;               // the order's key (docs/picks.md)
  std::uint32_t order = 0;        // 1: picked first; 0: no pick
  std::string reason;             // why not picked ("" with picks off)
};

// The pose found around one hypothesis (model to camera, mm).
struct Detection {
  Hypothesis hypothesis;
  std::uint32_t index = 0;          // the hypothesis' rank by height (0 = highest)
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  std::uint64_t votes = 0;          // of the pose's cluster
  std::uint32_t candidate = 0;      // which of the hypothesis' clusters (0 = most voted)
  std::uint32_t lookalike = 0;      // 0: the cluster's pose; k: its k-th look-alike
                                    // (host/train/lookalikes.hpp)
  PoseEvidence evidence;            // what verification measured (verified_pose.hpp)
  ScoreBreakdown breakdown;         // the score's factors (score.hpp); agreement 0: unverified
  std::string reason;               // why the score is 0 or refinement stopped early, or why the
                                    // hypothesis was skipped (Detector::skipped)
  // neighbourhood: points in the crop (from a depth image: pixels with data, whether or not
  // they have a normal, since normals are computed only for the points subsampling keeps).
  std::size_t neighbourhood = 0, subsampled = 0, refs = 0, peaks = 0, clusters = 0;
  PlannedPick pick;                 // with --picks: where to grasp it, or why not

  double score() const { return breakdown.score(); }  // verified, in [0, 1]: the ranking
  double fit_score() const { return breakdown.fit(); }  // before the look-alike share
};

}  // namespace binpick
