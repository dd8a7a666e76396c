// The shapes of the built-in parts at their natural size (mm, before builtin_parts.cpp centres
// them and scales them to their nominal diameters), with the symmetries they have in that frame.
#pragma once

#include "host/core/mesh.hpp"
#include "host/core/symmetry.hpp"

namespace binpick {

struct BuiltinShape {
  Mesh mesh;
  PartSymmetries symmetries;
};

// L-bracket: a base plate and a shorter upright plate at 90 degrees, one round hole in each.
BuiltinShape make_bracket_shape();

// Hex bolt: hexagonal head on a cylindrical shank with a chamfered tip, along +z.
BuiltinShape make_bolt_shape();

// Equal tee pipe fitting: a hollow run along x with a hollow branch along +z.
BuiltinShape make_tee_shape();

// Sheet-metal plate 1.5 thick in the xy plane, with two round holes and a slot laid out
// without symmetry.
BuiltinShape make_plate_shape();

// Stepped shaft along z, centred on the origin, with different steps at its two ends: only its
// axis is a symmetry.
BuiltinShape make_shaft_shape();

}  // namespace binpick
