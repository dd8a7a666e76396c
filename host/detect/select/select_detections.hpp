// From an image's verified poses to its detections: each hypothesis' best pose, ranked by the
// verified score (the paper's one detection per hypothesis), or with an instance budget every
// pose competes (instance_select.hpp).
#pragma once

#include <vector>

#include "host/detect/refine/candidate_poses.hpp"
#include "host/detect/select/detection.hpp"
#include "host/detect/verify/verified_pose.hpp"

namespace binpick {

// The order of the results: the verified score, ties to the more voted.
bool ranks_before(const Detection& a, const Detection& b);

// d becomes pose v, which came from `from`.
void take_pose(Detection& d, const VerifiedPose& v, const PoseOrigin& from);

// detections: one per hypothesis voted on (votes 0 until a pose is taken). Each takes its best
// pose (ties: the first, the more voted candidate); those without any pose are dropped; the
// rest are sorted by ranks_before, stably (ties keep height order).
std::vector<Detection> best_per_hypothesis(std::vector<Detection> detections,
                                           const std::vector<VerifiedPose>& poses,
                                           const std::vector<PoseOrigin>& origin);

// Every pose as a detection of its hypothesis, in pose order (for select_instances).
std::vector<Detection> every_pose(const std::vector<Detection>& detections,
                                  const std::vector<VerifiedPose>& poses,
                                  const std::vector<PoseOrigin>& origin);

}  // namespace binpick
