// The model options shared by every verb that takes a part (parts --info, synth, train, tune,
// run, bench): --model, --unit-scale, --diameter, --mesh; and the one place where the model
// argument is resolved: a file goes to the mesh loader, builtin:NAME to the built-in parts.
#pragma once

#include "host/core/cli_fwd.hpp"
#include <optional>
#include <string>

#include "host/formats/mesh/load_model.hpp"
#include "host/train/model_store.hpp"

namespace binpick::cli {

struct ModelArgs {
  std::string model;
  double unit_scale = 1;
  std::optional<double> diameter;
  std::string mesh;
};

void add_model_options(CLI::App* verb, ModelArgs& args, bool required = true);

ModelOptions model_options_of(const ModelArgs& args);
PartSpec part_spec_of(const ModelArgs& args);

// The part spec names ("builtin:NAME" or a model file), with its symmetries where known, scaled
// as its options say. Throws binpick::InputError naming spec.
Model load_part(const PartSpec& part);

// load_part, and for a model file, which states no symmetries, the ones found on its mesh
// (find_symmetries): what a dataset's models_info.json records. `found` tells which it was.
Model load_part_finding_symmetries(const PartSpec& part, bool* found = nullptr);

}  // namespace binpick::cli
