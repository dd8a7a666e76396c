// The look-alike share of verification: a pose is trusted only as far as it beats its own
// look-alike (docs/detect/verify.md, "Look-alike share").
//
// A part with look-alikes (a plate turned over, whose holes alone tell it from the plate the
// right way up) is refined and verified as each candidate and as each candidate's look-alikes
// (refine/candidate_poses.hpp). Where the factors cannot tell the two apart (the holes covered
// by another part, seen edge on, or lost in noise), both score alike and the better by chance is
// the detection. Such a score says how well the pose fits, not how sure the pose is; ranked by
// it, an ambiguous plate comes before an unambiguous one. So each pose's score s is multiplied
// by its share of the pair, s / (s + w a): a the best score among the poses refined from the
// same candidate (itself and its look-alikes, the in-plane search's pose and its look-alikes)
// whose centroid lies within `max_distance` of its own and which are turned from it by more than
// `min_turn_deg`, that is the same part another way round. A tie halves the score; a look-alike
// scoring nothing leaves it. Poses of other candidates are not counted: two candidates may be
// two parts side by side. Figures: docs/decisions/2026-12-02-lookalike-share.md.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "host/detect/verify/verified_pose.hpp"

namespace binpick {

// Look-alikes lie within this fraction of the diameter of each other: the same part, at the
// loose criterion's translation error (docs/parameters.md, "Evaluation").
inline constexpr double kLookalikeRatio = 0.1;

struct LookalikeOptions {
  double weight = 1.0;        // w; 0: off
  double max_distance = 0.0;  // mm, between posed centroids
  double min_turn_deg = 30.0;
};

// group[i]: the candidate pose i was refined from (one id per candidate); centroid: the
// model's centroid in the model frame. Sets each pose's lookalike_score (evidence) and its
// look-alike share factor (score.hpp, lookalike_share_factor), against the poses' fits.
void lookalike_share(std::vector<VerifiedPose>& poses, const std::vector<std::size_t>& group,
                     const Eigen::Vector3d& centroid, const LookalikeOptions& opt);

}  // namespace binpick
