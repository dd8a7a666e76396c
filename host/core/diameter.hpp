// The exact diameter of a part: the largest distance between two of its points. It sets the
// scale of everything in the method (voxel size, distance steps, error thresholds).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace binpick {

// Largest distance between two of the points (0 for fewer than two). The farthest pair lies on
// the convex hull, so only hull vertices are compared (in double); the pairwise search is
// pruned by distance from the centre and stays exact.
double exact_diameter(const std::vector<Eigen::Vector3f>& points);

}  // namespace binpick
