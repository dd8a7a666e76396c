// What detection returns for one pose: the pose, its verified score and what the score is made
// of, the votes, and where it came from (hypothesis, candidate, look-alike).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "host/detect/hypotheses/hypotheses.hpp"

namespace binpick {

// The pose found around one hypothesis (model to camera, mm).
struct Detection {
  Hypothesis hypothesis;
  std::uint32_t index = 0;          // the hypothesis' rank by height (0 = highest)
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double score = 0;                 // verified score in [0, 1] (pose_refine.hpp): the ranking
  std::uint64_t votes = 0;          // of the pose's cluster
  std::uint32_t candidate = 0;      // which of the hypothesis' clusters (0 = most voted)
  std::uint32_t twin = 0;           // 0: the cluster's pose; k: its k-th near-symmetric copy
                                    // (near_symmetry.hpp)
  std::uint32_t visible = 0, inliers = 0;  // model points seen at the pose, and agreeing
  // Outline cells where the measured surface runs on past the part's edge, and where it steps
  // down (both 0 without the outline test: pose_fit_shared.h).
  std::uint32_t outline_continue = 0, outline_step = 0;
  // Model patches tested and found biased by the patch test (patch_bias.hpp; 0 without it).
  std::uint32_t patches_tested = 0, patches_biased = 0;
  // The ray test's excess RMS along the rays beyond the image's noise (mm; ray_spread.hpp), if run.
  bool ray_tested = false;
  double ray_excess = 0;
  // The twin test's largest mean depth excess at a look-alike's probes (mm; lookalike_holes.hpp).
  bool twin_tested = false;
  double twin_excess = 0;
  // The edge test's step down at the part's edges (mm, an upper bound; edge_step.hpp), if run.
  bool edge_tested = false;
  double edge_step = 0;
  // The seen-area test's share: the area the pose shows over the part's mean (seen_area.hpp).
  bool area_tested = false;
  double area_share = 0;
  // The rival test (rival.hpp): out-fitted by another pose on this many shared measured
  // points, its mean clipped squared residual there against the rival's (mm^2).
  bool rival_out_fitted = false;
  std::uint32_t rival_shared = 0;
  double own_ms = 0, rival_ms = 0;
  double lookalike_score = 0;  // its best look-alike's score (lookalike_share.hpp); 0 if none
  double fit_score = 0;  // its score before the look-alike share
  std::uint32_t see_through = 0;    // visible model points the sensor sees past
  std::string reason;               // why the score is 0 or refinement stopped early, or why the
                                    // hypothesis was skipped (Detector::skipped)
  // neighbourhood: points in the crop (from a depth image: pixels with data, whether or not
  // they have a normal, since normals are computed only for the points subsampling keeps).
  std::size_t neighbourhood = 0, subsampled = 0, refs = 0, peaks = 0, clusters = 0;
};

}  // namespace binpick
