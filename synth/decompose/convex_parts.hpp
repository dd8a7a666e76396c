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

}  // namespace binpick
