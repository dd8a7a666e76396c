// A refined pose after verification: what verification measured of it (the inputs of the
// score's factors) and the factors themselves (score.hpp). Detection carries the same two.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/detect/verify/score.hpp"

namespace binpick {

struct PoseEvidence {
  // Model points by class at the final pose (pose_fit_shared.h): visible = all but hidden.
  std::uint32_t visible = 0, missing = 0, inliers = 0, see_through = 0, occluded = 0;
  std::uint32_t outline_continue = 0, outline_step = 0;  // outline cells (0 without the test)
  std::uint32_t patches_tested = 0, patches_biased = 0;  // patch_bias.hpp (0 without it)
  bool ray_tested = false;
  double ray_excess = 0;        // mm, RMS along the rays beyond the image's noise
  bool lookalike_tested = false;
  double lookalike_excess = 0;  // mm, the largest depth excess at a look-alike's probes
  bool edge_tested = false;
  double edge_step = 0;         // mm, the step down at its edges (an upper bound)
  bool area_tested = false;
  double area_share = 0;        // its seen area over the part's mean area
  // The rival: out-fitted on this many shared measured points, with these mean clipped squared
  // residuals there (mm^2): its own and the rival's.
  std::uint32_t rival_shared = 0;
  double own_ms = 0, rival_ms = 0;
  double lookalike_score = 0;   // the best score of its look-alikes before their shares; 0: none
  float tolerance = 0;          // mm, the verification tolerance (the same for an image's poses)
};

struct VerifiedPose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  std::uint32_t iterations = 0;  // ICP steps taken
  PoseEvidence evidence;
  ScoreBreakdown breakdown;
  // The measured points of its ICP terms at the final pose, for the rival (depth images only).
  std::vector<Eigen::Vector3f> measured;
  std::string reason;  // why the score is 0 or refinement stopped early; empty if neither

  double score() const { return breakdown.score(); }
  double fit_score() const { return breakdown.fit(); }
};

}  // namespace binpick
