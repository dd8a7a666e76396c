// Which side of a CAD mesh is outside. Training takes surface normals from the triangles'
// winding (counter-clockwise seen from outside), and detection matches them with scene normals
// that point at the camera, i.e. out of the part: a mesh wound the other way round (inside out,
// common in STL files from the wild) would never be found, and one wound inconsistently would
// be found only in part.
#pragma once

#include <cstddef>

#include "host/core/mesh.hpp"

namespace binpick {

struct OrientationReport {
  std::size_t components = 0;      // pieces connected through shared edges
  std::size_t closed = 0;          // of them, closed (every edge shared by two triangles)
  std::size_t made_consistent = 0; // triangles turned to agree with their neighbours
  std::size_t turned_out = 0;      // triangles of pieces that were inside out, turned
  std::size_t undecided = 0;       // triangles of open pieces without file normals to go by
  bool normals_flipped = false;    // the file's vertex normals pointed inwards and were negated
};

// Orients every triangle so its winding is counter-clockwise seen from outside:
//   1. within each piece (triangles joined through edges shared by exactly two triangles,
//      vertices welded by position), turn triangles to agree with their neighbours;
//   2. a closed piece with negative signed volume is inside out: turn it; so is an open piece
//      that still encloses a tenth of its bounding box with negative volume (a scan with holes);
//   3. any other piece (a sheet, a sliver, a flat artefact: no volume to go by) follows the
//      file's vertex normals if the mesh has them (most faces agreeing decides), else it stays
//      as wound (undecided).
// Then, if the file's vertex normals disagree with the faces for most triangles, they are
// negated. Positions are not changed.
OrientationReport orient_outward(Mesh& mesh);

}  // namespace binpick
