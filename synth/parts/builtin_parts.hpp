// Built-in parametric industrial parts, so the whole pipeline runs without a CAD file:
// `--model builtin:NAME`. Each is a closed, outward-oriented mesh with true (unaveraged)
// normals at sharp edges, centred on its bounding box and scaled to its nominal diameter: the
// paper's 52 mm for most, but a sheet-metal plate keeps its real 120 mm, since at 52 mm it would
// be a 0.6 mm foil.
#pragma once

#include <string>
#include <vector>

#include "host/core/mesh.hpp"
#include "host/core/symmetry.hpp"

namespace binpick {

constexpr double builtin_part_diameter = 52.0;  // mm, the part size of the paper

// In a fixed order: bracket, bolt, tee, plate, shaft.
std::vector<std::string> builtin_part_names();

// The exact diameter (mm) of make_builtin_part(name): builtin_part_diameter, or 120 for the
// plate.
double builtin_part_nominal_diameter(const std::string& name);

// One line saying what the part is. Throws binpick::InputError for an unknown name (listing
// the known ones), like the functions above and below.
std::string builtin_part_description(const std::string& name);

Mesh make_builtin_part(const std::string& name);

// The part's symmetries in the frame of make_builtin_part(name).
PartSymmetries builtin_part_symmetries(const std::string& name);

}  // namespace binpick
