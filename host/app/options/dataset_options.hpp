// The options of the synthetic bins a verb makes, registered once for every verb that makes
// them (synth, run, tune, bench): --bins, --objects, --seed, --width, --height and, where the
// verb runs the physics to the end, --max-wall-seconds. Each verb starts from its own defaults.
#pragma once

#include <cstdint>
#include <string>

#include "host/core/cli_fwd.hpp"

namespace binpick::cli {

struct DatasetArgs {
  int bins = 30;
  int objects = 350;
  std::uint64_t seed = 1;
  std::uint32_t width = 1600, height = 900;
  double max_wall_seconds = 0;  // per bin's physics, 0 = unlimited
};

// bins_help says what --bins counts for this verb ("bins per noise level").
void add_dataset_options(CLI::App* verb, DatasetArgs& args, const std::string& bins_help,
                         bool with_wall_limit = true);

// Copies the fields into any options struct that names them like DatasetArgs does.
template <class Options>
void apply_dataset_args(const DatasetArgs& a, Options& o) {
  o.bins = a.bins;
  o.objects = a.objects;
  o.seed = a.seed;
  o.width = a.width;
  o.height = a.height;
}

}  // namespace binpick::cli
