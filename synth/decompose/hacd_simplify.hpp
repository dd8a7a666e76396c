// A mesh simplified for HACD. HACD's time grows much faster than the triangle count (a few
// thousand triangles can take hours: docs/decisions/2026-11-28-hacd-simplify.md), while CAD
// exports often have tens of thousands. The hulls only give the physics its shape, and they are
// grown afterwards to cover every vertex of the original mesh (hull_cover.hpp), so HACD may see
// a coarser mesh: quadric edge collapse (meshoptimizer's meshopt_simplify, which keeps the
// topology, so a hole stays a hole) down to the target, then, if that stops short, vertex
// clustering (meshopt_simplifySloppy) for the rest.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace binpick {

// Points and triangles (indices into the points) as HACD takes them.
struct HacdMesh {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<long, 3>> triangles;
};

// `mesh` unchanged if it has at most `limit` triangles; else simplified to at most `target`
// (target <= limit), unused points dropped, deterministic. Throws std::invalid_argument if
// target is 0 or above limit.
HacdMesh simplify_for_hacd(const HacdMesh& mesh, std::size_t limit, std::size_t target);

}  // namespace binpick
