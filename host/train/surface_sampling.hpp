// Uniform points on a mesh's surface: CAD meshes put vertices only along feature edges, so the
// model is built from points sampled by area instead (the paper re-meshes with approximated
// centroidal Voronoi diagrams; dense random sampling followed by voxel subsampling gives the same
// evenly spread points at the voxel resolution).
#pragma once

#include <cstdint>

#include "host/core/mesh.hpp"

namespace binpick {

inline constexpr std::uint64_t kSurfaceSamplingSeed = 0x62696e7069636b31ull;  // "binpick1"

// count points, each on a triangle chosen with probability proportional to its area, uniform
// within it, with that triangle's face normal (triangles are counter-clockwise seen from outside;
// face normals are never averaged across sharp edges). Deterministic for a given seed on every
// platform (no std distributions). Throws InputError if the mesh has no triangle of positive
// area or a non-finite or out-of-range vertex.
PointCloud sample_surface(const Mesh& mesh, std::size_t count,
                          std::uint64_t seed = kSurfaceSamplingSeed);

// Total area of the triangles (in double).
double surface_area(const Mesh& mesh);

}  // namespace binpick
