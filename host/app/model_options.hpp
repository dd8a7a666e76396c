// The model options shared by every verb that takes a part (parts --info, synth, train):
// --model, --unit-scale, --diameter, --mesh.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "host/formats/mesh/load_model.hpp"

namespace binpick::cli {

struct ModelArgs {
  std::string model;
  double unit_scale = 1;
  std::optional<double> diameter;
  std::string mesh;
};

void add_model_options(CLI::App* verb, ModelArgs& args, bool required = true);

ModelOptions model_options_of(const ModelArgs& args);

// Loads the model the options name (throws binpick::InputError).
Mesh load_model(const ModelArgs& args);
Model load_model_with_symmetries(const ModelArgs& args);

}  // namespace binpick::cli
