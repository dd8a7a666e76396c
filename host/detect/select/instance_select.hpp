// The instance budget (DetectParams::instances): for BOP's recall, which counts every annotated
// part, an image's detections are its N best verified poses of different parts rather than one
// per hypothesis. Every refined candidate of every hypothesis competes; a pose whose part
// centroid lies within a quarter of the diameter of a better one is the same part found twice
// (two hypotheses on one part, or a candidate and its look-alike) and is dropped.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "host/detect/select/detection.hpp"

namespace binpick {

// Two poses whose posed model centroids are closer than this fraction of the diameter are one
// part.
inline constexpr double kDuplicateRatio = 0.25;

// Of `poses` (in hypothesis, candidate, look-alike order): those with a score above 0, best first
// (score, then votes, then that order), each kept only if its posed centroid (R c + t, c in the
// model frame) lies at least `min_distance` from every pose kept before it; at most `budget`.
std::vector<Detection> select_instances(std::vector<Detection> poses,
                                        const Eigen::Vector3d& centroid, double min_distance,
                                        std::size_t budget);

}  // namespace binpick
