#include "host/app/options/train_options.hpp"

#include <CLI/CLI.hpp>
#include <cmath>

#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick::cli {
namespace {

std::uint32_t steps(std::int64_t value, const char* option, std::int64_t lo, std::int64_t hi) {
  if (value < lo || value > hi)
    throw InputError(fmt::format("{} {} must be in [{}, {}]", option, value, lo, hi));
  return static_cast<std::uint32_t>(value);
}

}  // namespace

void add_train_options(CLI::App* verb, TrainArgs& args, const std::string& what) {
  const auto help = [&](const std::string& text) { return what + ": " + text; };
  verb->add_option("--voxel-ratio", args.voxel_ratio,
                   help("subsampling voxel size as a fraction of the diameter, in (0, 1]"))
      ->capture_default_str();
  verb->add_option("--distance-steps", args.distance_steps,
                   help("distance bins up to the diameter, in [1, 1000]"))
      ->capture_default_str();
  verb->add_option("--angle-steps", args.angle_steps,
                   help("angle bins of a full turn (30 = 12 degrees), in [4, 360]; feature "
                        "angles in [0, pi] get half as many"))
      ->capture_default_str();
  verb->add_option("--cup-diameter", args.cup_diameter,
                   help(fmt::format("the suction cup the grasps generated from the part's flat "
                                    "faces are for, mm (0: {:g} % of the diameter)",
                                    100 * kDefaultCupRatio)))
      ->capture_default_str();
}

PpfTrainParams train_params_of(const TrainArgs& a) {
  PpfTrainParams p;
  if (!(std::isfinite(a.voxel_ratio) && a.voxel_ratio > 0 && a.voxel_ratio <= 1))
    throw InputError(fmt::format("--voxel-ratio {} must be in (0, 1] (a fraction of the diameter)",
                                 a.voxel_ratio));
  p.voxel_ratio = a.voxel_ratio;
  p.distance_steps = steps(a.distance_steps, "--distance-steps", 1, 1000);
  p.angle_steps = steps(a.angle_steps, "--angle-steps", 4, 360);
  if (!(std::isfinite(a.cup_diameter) && a.cup_diameter >= 0 && a.cup_diameter < 1e6))
    throw InputError(fmt::format("--cup-diameter {} must be positive (mm), or 0 for {:g} % of "
                                 "the diameter", a.cup_diameter, 100 * kDefaultCupRatio));
  p.cup_diameter = a.cup_diameter;
  check_train_params(p);
  return p;
}

}  // namespace binpick::cli
