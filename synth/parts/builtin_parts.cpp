#include "synth/parts/builtin_parts.hpp"

#include "host/core/error.hpp"
#include "host/core/diameter.hpp"
#include "host/core/mesh_geometry.hpp"
#include "synth/parts/part_shapes.hpp"

namespace binpick {
namespace {

struct BuiltinPart {
  const char* name;
  const char* description;
  BuiltinShape (*make_shape)();
  double diameter;  // mm, exact after normalized()
};

constexpr BuiltinPart parts[] = {
    {"bracket", "L-bracket: two plates at 90 degrees, unequal legs, a round hole in each",
     &make_bracket_shape, builtin_part_diameter},
    {"bolt", "hex bolt: hexagonal head on a round shank with a chamfered tip (sixfold symmetric)",
     &make_bolt_shape, builtin_part_diameter},
    {"tee", "equal tee pipe fitting: hollow run with a hollow branch at 90 degrees",
     &make_tee_shape, builtin_part_diameter},
    // A sheet-metal part at its real size: scaled to 52 mm it would be 0.6 mm thick.
    {"plate",
     "sheet-metal plate, 1.5 mm thick and 120 mm across, with two round holes and a slot "
     "(no symmetry)",
     &make_plate_shape, 120},
    {"shaft",
     "stepped shaft: four round steps of different diameters, 4.6 times as long as wide "
     "(symmetric about its axis only)",
     &make_shaft_shape, builtin_part_diameter},
};

const BuiltinPart& find_part(const std::string& name) {
  for (const auto& part : parts) {
    if (name == part.name) return part;
  }
  std::string known;
  for (const auto& part : parts) known += (known.empty() ? "" : ", ") + std::string(part.name);
  throw InputError("unknown built-in part '" + name + "' (known: " + known + ")");
}

// The shape moved so its bounding box is centred on the origin and scaled about the origin to
// the part's nominal diameter; its symmetries follow (a symmetry S becomes T S T^-1).
BuiltinShape normalized(const BuiltinPart& part) {
  BuiltinShape shape = part.make_shape();
  const Eigen::Vector3f centre = bounding_box(shape.mesh.positions).center();
  translate_mesh(shape.mesh, -centre);
  for (auto& s : shape.symmetries.continuous) s.offset -= centre.cast<double>();
  for (auto& m : shape.symmetries.discrete) {
    const Eigen::Vector3d c = centre.cast<double>();
    m.block<3, 1>(0, 3) += m.topLeftCorner<3, 3>() * c - c;
  }
  const double factor = part.diameter / exact_diameter(shape.mesh.positions);
  scale_mesh(shape.mesh, factor);
  shape.symmetries = shape.symmetries.scaled(factor);
  return shape;
}

}  // namespace

std::vector<std::string> builtin_part_names() {
  std::vector<std::string> names;
  for (const auto& part : parts) names.emplace_back(part.name);
  return names;
}

double builtin_part_nominal_diameter(const std::string& name) { return find_part(name).diameter; }

std::string builtin_part_description(const std::string& name) {
  return find_part(name).description;
}

Mesh make_builtin_part(const std::string& name) { return normalized(find_part(name)).mesh; }

PartSymmetries builtin_part_symmetries(const std::string& name) {
  return normalized(find_part(name)).symmetries;
}

}  // namespace binpick
