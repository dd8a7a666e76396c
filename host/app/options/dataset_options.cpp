#include "host/app/options/dataset_options.hpp"
#include <CLI/CLI.hpp>

namespace binpick::cli {

void add_dataset_options(CLI::App* verb, DatasetArgs& a, const std::string& bins_help,
                         bool with_wall_limit) {
  verb->add_option("--bins", a.bins, bins_help)->capture_default_str();
  verb->add_option("--objects", a.objects,
                   "parts per bin (more than the bin holds, estimated from the part's volume, "
                   "is refused)")->capture_default_str();
  verb->add_option("--seed", a.seed, "random seed of the bins: the same seed gives the same bins")
      ->capture_default_str();
  verb->add_option("--width", a.width, "image width, pixels")->capture_default_str();
  verb->add_option("--height", a.height, "image height, pixels")->capture_default_str();
  if (with_wall_limit)
    verb->add_option("--max-wall-seconds", a.max_wall_seconds,
                     "wall-clock limit of one bin's physics (0: none); a bin cut short says so and "
                     "names the parts not at rest")
        ->capture_default_str();
}

}  // namespace binpick::cli
