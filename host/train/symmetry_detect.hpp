// The rotational symmetries of a part, found on its mesh, so that a CAD file nobody stated
// symmetries for is clustered and evaluated like a built-in part: a pose and its symmetric copy
// are the same pose.
//
// A rotation R about the surface centroid c is a symmetry when x -> R (x - c) + c maps the
// surface onto itself: at most kSymmetryMissRatio of 2000 test points (surface samples of their
// own seed) land farther than kSymmetryDistanceRatio of the diameter from a dense reference
// sampling of the surface (spacing 0.4 % of the diameter, 20 000 to 400 000 points), or land
// near it facing another way (normals more than kSymmetryNormalDeg apart; this tells the two
// faces of a thin sheet apart).
//
// Every rotation axis of a symmetry is a principal axis of the surface's inertia, so the
// candidates are few. The inertia comes from exact surface moments of the triangles, so an
// exactly symmetric mesh has exactly symmetric principal axes; moments within 1 % of the largest
// count as equal, and the principal axes of equal moments are arbitrary in their plane:
//   - candidate axes: the three principal axes; with two equal moments only the third (any
//     other symmetry axis lies in the plane of the two and can only be a half turn); with
//     three equal moments (a cube, a regular polyhedron, a sphere) also the 12 largest
//     face-normal directions and the directions to the 12 farthest vertices;
//   - each candidate: continuous if rotations by 0.37, 1.1, 2.3 and 3.9 rad all pass, else the
//     largest n <= kSymmetryMaxFold all of whose n - 1 rotations by multiples of 2 pi / n pass
//     (not only the first, nor only those up to a half turn: on a nearly round part a turn can
//     pass and its inverse fail, which is no group);
//   - half turns about the axes perpendicular to a candidate found n-fold with n >= 3, or to
//     one whose perpendicular moments are equal: a scan of the directions over [0, pi / n) in
//     0.5 degree steps on 128 test points, each run of passing steps refined in 0.05 degree
//     steps by the mean distance to the surface's tangent planes, then the full test. A
//     continuous axis needs one perpendicular direction: all are equivalent.
// The discrete result is the group the passing rotations generate (products merged within
// 5 degrees), every element tested again; at most kMaxFoundSymmetries elements with the
// identity. One continuous axis comes with at most one discrete symmetry, the half turn that
// swaps its ends (the BOP convention); two continuous axes mean a sphere (no discrete ones).
#pragma once

#include <cstddef>

#include "host/core/mesh.hpp"
#include "host/core/symmetry.hpp"

namespace binpick {

inline constexpr double kSymmetryDistanceRatio = 0.01;  // of the diameter
inline constexpr double kSymmetryNormalDeg = 30.0;
inline constexpr double kSymmetryMissRatio = 0.01;  // of the test points
// A gear's teeth: a 14-tooth gear came out 7-fold at 12, and a pose one tooth off as wrong.
inline constexpr int kSymmetryMaxFold = 24;
inline constexpr std::size_t kMaxFoundSymmetries = 64;  // group elements, the identity included

// The symmetries in the mesh's own frame (mm), in the BOP models_info.json convention:
// continuous axes through the centroid, discrete 4x4 rigid transforms (not the identity) in a
// fixed order. Deterministic. Throws InputError for a mesh with no surface or no extent.
PartSymmetries find_symmetries(const Mesh& mesh);

}  // namespace binpick
