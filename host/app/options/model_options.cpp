#include "host/app/options/model_options.hpp"

#include <CLI/CLI.hpp>
#include <string_view>

#include "host/core/error.hpp"
#include "host/train/symmetry_detect.hpp"
#include "synth/parts/builtin_parts.hpp"

namespace binpick::cli {
namespace {

constexpr std::string_view builtin_prefix = "builtin:";

}  // namespace

void add_model_options(CLI::App* verb, ModelArgs& args, bool required) {
  std::string builtins;
  for (const auto& name : builtin_part_names()) builtins += (builtins.empty() ? "" : ", ") + name;
  auto* model = verb->add_option("--model", args.model,
                                 "part model: file (.gltf .glb .ply .stl .obj) or builtin:NAME "
                                 "(built-in: " +
                                     builtins + ")");
  if (required) model->required();
  verb->add_option("--unit-scale", args.unit_scale,
                   "multiply file coordinates by this to get mm (1000 for a file in metres; "
                   "STL has no units)")
      ->capture_default_str();
  verb->add_option("--diameter", args.diameter,
                   "rescale the part uniformly about its origin to this exact diameter (mm)");
  verb->add_option("--mesh", args.mesh, "glTF only: use the node or mesh of this name");
}

ModelOptions model_options_of(const ModelArgs& args) {
  return {args.unit_scale, args.diameter, args.mesh};
}

PartSpec part_spec_of(const ModelArgs& args) {
  return {args.model, model_options_of(args)};
}

Model load_part(const PartSpec& part) {
  if (!part.spec.starts_with(builtin_prefix))
    return load_model_with_symmetries(part.spec, part.options);
  const std::string name = part.spec.substr(builtin_prefix.size());
  if (!part.options.mesh_name.empty())
    throw InputError(part.spec +
                     ": --mesh selects a node of a glTF file, not of a built-in part");
  Mesh mesh;
  try {
    mesh = make_builtin_part(name);
  } catch (const InputError& e) {
    throw InputError(part.spec + ": " + e.what());
  }
  return complete_model(std::move(mesh), builtin_part_symmetries(name), part.spec, part.options);
}

Model load_part_finding_symmetries(const PartSpec& part, bool* found) {
  Model model = load_part(part);
  const bool file = !part.spec.starts_with(builtin_prefix);
  if (file) model.symmetries = find_symmetries(model.mesh);
  if (found) *found = file;
  return model;
}

}  // namespace binpick::cli
