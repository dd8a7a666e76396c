// Per-vertex normals for meshes whose files carry none, and clean-up of normals read from files.
#pragma once

#include "host/core/mesh.hpp"

namespace binpick {

// Replaces mesh.normals by area-weighted averages of the face normals around each vertex, but
// only across edges whose faces meet within crease_angle_degrees: a vertex on a sharp edge is
// split into one vertex per side so each face keeps its true normal (as in the built-in parts),
// while curved surfaces get smooth normals. Weld the mesh first (merge_duplicate_vertices):
// faces are joined only through shared vertex indices.
void compute_crease_normals(Mesh& mesh, double crease_angle_degrees = 30.0);

// The mesh itself if it has one normal per vertex, else a welded copy with crease normals:
// what the writers of formats with normals store.
Mesh with_normals(const Mesh& mesh);

// Scales every normal to unit length (some files store non-unit normals). Returns false, and
// leaves the normals unusable, if any normal is zero or not finite.
bool normalize_normals(Mesh& mesh);

}  // namespace binpick
