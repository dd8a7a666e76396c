#include "host/app/model_options.hpp"

#include "synth/parts/builtin_parts.hpp"

namespace binpick::cli {

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

Mesh load_model(const ModelArgs& args) {
  return binpick::load_model(args.model, model_options_of(args));
}

Model load_model_with_symmetries(const ModelArgs& args) {
  return binpick::load_model_with_symmetries(args.model, model_options_of(args));
}

}  // namespace binpick::cli
