#include "host/detect/select/instance_select.hpp"

#include <algorithm>

namespace binpick {

std::vector<Detection> select_instances(std::vector<Detection> poses,
                                        const Eigen::Vector3d& centroid, double min_distance,
                                        std::size_t budget) {
  // Score 0 is a pose verification rejected (or one below the floor): not a part.
  std::erase_if(poses, [](const Detection& d) { return !(d.score() > 0) || d.votes == 0; });
  std::stable_sort(poses.begin(), poses.end(), [](const Detection& a, const Detection& b) {
    if (a.score() != b.score()) return a.score() > b.score();
    return a.votes > b.votes;
  });
  std::vector<Detection> kept;
  std::vector<Eigen::Vector3d> centres;
  const double min2 = min_distance * min_distance;
  for (Detection& d : poses) {
    if (kept.size() >= budget) break;
    const Eigen::Vector3d c = d.R * centroid + d.t;
    const bool duplicate = std::any_of(centres.begin(), centres.end(), [&](const Eigen::Vector3d& k) {
      return (k - c).squaredNorm() < min2;
    });
    if (duplicate) continue;
    centres.push_back(c);
    kept.push_back(std::move(d));
  }
  return kept;
}

}  // namespace binpick
