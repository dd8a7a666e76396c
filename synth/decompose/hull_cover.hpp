// Makes the hulls cover the mesh. HACD simplifies each cluster's hull to max_hull_vertices by
// cutting corners, so parts of the surface can stick out of every hull: with 12 vertices the
// built-in bolt's mesh lay up to 5 mm outside its hulls (a fifth of its volume), the test torus's
// up to 1.7 mm. Bullet only sees the hulls, so two rendered parts could then overlap by the sum.
#pragma once

#include "host/core/mesh.hpp"
#include "synth/decompose/convex_parts.hpp"

namespace binpick {

// Every mesh vertex lying farther than `tolerance_mm` outside all hulls is added to the hull
// it is nearest to (the one it lies least outside of), and that hull rebuilt, until none is.
// Hulls grow only where the mesh sticks out, so they keep few vertices where HACD's fit well.
ConvexParts cover_mesh(const ConvexParts& parts, const Mesh& mesh, double tolerance_mm);

// How far the mesh vertex farthest outside every hull lies outside it (mm); 0 when all are in.
double farthest_outside_mm(const ConvexParts& parts, const Mesh& mesh);

}  // namespace binpick
