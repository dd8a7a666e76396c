// The training options, registered once for every verb that trains a model (train, run, tune):
// --voxel-ratio, --distance-steps, --angle-steps, --cup-diameter (docs/parameters.md).
#pragma once

#include <cstdint>
#include <string>

#include "host/core/cli_fwd.hpp"

#include "host/train/ppf_model.hpp"

namespace binpick::cli {

struct TrainArgs {
  double voxel_ratio = PpfTrainParams{}.voxel_ratio;
  // Wide types, so that a negative or huge value reaches the range check (a message that says
  // what is allowed) instead of a conversion error.
  std::int64_t distance_steps = BP_PPF_DEFAULT_DIST_STEPS;
  std::int64_t angle_steps = BP_PPF_DEFAULT_ANGLE_STEPS;
  double cup_diameter = 0;  // 0: kDefaultCupRatio of the diameter
};

// Adds the options to verb; `what` starts each help text ("training", "starting point").
void add_train_options(CLI::App* verb, TrainArgs& args, const std::string& what);

// The parameters the options give; InputError naming the option for a value out of range.
PpfTrainParams train_params_of(const TrainArgs& args);

}  // namespace binpick::cli
