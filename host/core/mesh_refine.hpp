// Refining a mesh until its vertices are dense everywhere: BOP's models_eval/ (the vertex set
// its MSSD and MSPD errors take the maximum over) are its models resampled to a roughly uniform
// density (bop_toolkit's remesh_models_for_eval.py: MeshLab's uniform resampling, then
// decimation). binpick keeps the exact surface instead and only adds vertices: every edge
// longer than the limit is split at its midpoint, in passes, until none is. Dense regions stay
// as they are (no decimation).
#pragma once

#include "host/core/mesh.hpp"

namespace binpick {

// Splits shared edges once for both triangles (no T-junctions), keeps the winding; a new
// vertex's normal is the normalised mean of its edge's (when the mesh has normals).
// InputError unless max_edge_mm > 0 and every triangle index is a vertex.
Mesh split_long_edges(const Mesh& mesh, double max_edge_mm);

}  // namespace binpick
