// The options that say what a synthetic bin looks like beyond the paper's: the bin in view,
// other parts mixed in, a tilted camera and the depth sensor. Declared once for `synth` and
// `run` (which makes a dataset per noise level with them).
#pragma once

#include <string>

#include "host/core/cli_fwd.hpp"

#include "synth/synthesize.hpp"

namespace binpick::cli {

struct SceneArgs {
  std::string bin_render = "full";
  std::string distractors;
  double camera_tilt_deg = 0.0;
  double camera_roll_deg = 0.0;
  SensorModel sensor;
};

void add_scene_options(CLI::App* verb, SceneArgs& args);

// Copies the options into o (throws InputError for a malformed --distractors).
void apply_scene_args(const SceneArgs& args, SynthOptions& o);

}  // namespace binpick::cli
