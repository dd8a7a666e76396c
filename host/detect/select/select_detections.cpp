#include "host/detect/select/select_detections.hpp"

#include <algorithm>

namespace binpick {

bool ranks_before(const Detection& a, const Detection& b) {
  if (a.score() != b.score()) return a.score() > b.score();
  return a.votes > b.votes;
}

void take_pose(Detection& d, const VerifiedPose& v, const PoseOrigin& from) {
  d.R = v.R;
  d.t = v.t;
  d.votes = from.votes;
  d.candidate = from.candidate;
  d.lookalike = from.lookalike;
  d.evidence = v.evidence;
  d.breakdown = v.breakdown;
  d.reason = v.reason;
}

std::vector<Detection> best_per_hypothesis(std::vector<Detection> detections,
                                           const std::vector<VerifiedPose>& poses,
                                           const std::vector<PoseOrigin>& origin) {
  std::vector<bool> taken(detections.size(), false);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const std::size_t k = origin[i].hypothesis;
    Detection& d = detections[k];
    // The best score; ties go to the more voted cluster, which comes first.
    if (taken[k] && poses[i].score() <= d.score()) continue;
    taken[k] = true;
    take_pose(d, poses[i], origin[i]);
  }
  std::erase_if(detections, [](const Detection& d) { return d.votes == 0; });
  std::stable_sort(detections.begin(), detections.end(), ranks_before);
  return detections;
}

std::vector<Detection> every_pose(const std::vector<Detection>& detections,
                                  const std::vector<VerifiedPose>& poses,
                                  const std::vector<PoseOrigin>& origin) {
  std::vector<Detection> out;
  out.reserve(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    Detection d = detections[origin[i].hypothesis];
    take_pose(d, poses[i], origin[i]);
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace binpick
