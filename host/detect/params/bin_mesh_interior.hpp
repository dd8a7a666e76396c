// A bin given as a mesh (`--bin mesh:FILE`): its interior size, for the sized fit (bin_fit.hpp).
// The mesh is in the frame of synth's `--bin-mesh` (docs/cli.md): mm, origin at the centre of
// the interior floor, floor at z = 0, z up. The interior is what rays from the floor's centre
// line reach: along +-x and +-y, from a grid of points over the middle half of the other side
// and 20-80 % of the height, the nearest wall any ray meets (a wire basket's rays may pass
// between its bars; one that meets a bar is enough). Its height is the mesh's top (a rim tube's,
// which the fit sees as the rim).
#pragma once

#include <Eigen/Core>

#include "host/core/mesh.hpp"

namespace binpick {

// W, D, H (mm), W >= D. InputError when the mesh has nothing above z = 0 or a side meets no ray
// (not a bin, or not in that frame).
Eigen::Vector3d bin_interior_from_mesh(const Mesh& mesh);

// The nearest hit along the ray o + s d (s > 0) of a triangle seen from either side, or a
// negative value for none (Moller-Trumbore).
double ray_triangle_distance(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                             const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& c);

}  // namespace binpick
