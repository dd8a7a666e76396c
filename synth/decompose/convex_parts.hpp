// The collision stand-in of a part: a few convex hulls whose union approximates the mesh.
// The physics collides these (convex pairs are cheap); rendering uses the original mesh.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace binpick {

struct ConvexHull {
  std::vector<Eigen::Vector3f> vertices;  // mm, in the part's frame
};

struct ConvexParts {
  std::vector<ConvexHull> hulls;
};

// The smallest extent of a hull along its principal axes (mm): how thin it is. Decomposition
// drops flat hulls by it; the drop sizes its adaptive step by the thinnest hull.
double thinnest_extent(const ConvexHull& hull);

}  // namespace binpick
