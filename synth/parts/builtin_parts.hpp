// Built-in parametric industrial parts, so the whole pipeline runs without a CAD file:
// `--model builtin:NAME`. Each is a closed, outward-oriented mesh with true (unaveraged)
// normals at sharp edges, centred on its bounding box and scaled to the paper's 52 mm diameter.
#pragma once

#include <string>
#include <vector>

#include "host/core/mesh.hpp"
#include "host/core/symmetry.hpp"

namespace binpick {

constexpr double builtin_part_diameter = 52.0;  // mm, the part size of the paper

// In a fixed order: bracket, bolt, tee.
std::vector<std::string> builtin_part_names();

// One line saying what the part is. Throws binpick::InputError for an unknown name (listing
// the known ones), like the two functions below.
std::string builtin_part_description(const std::string& name);

Mesh make_builtin_part(const std::string& name);

// The part's symmetries in the frame of make_builtin_part(name).
PartSymmetries builtin_part_symmetries(const std::string& name);

}  // namespace binpick
