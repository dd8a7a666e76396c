// `binpick tune`: chooses detection parameters automatically (paper III-D: the whole loop is
// automatic, so it can tune itself). Searches reference ratio, clustering thresholds, exclusion
// radius and the model's angle and distance steps on a small synthetic dataset, maximising
// top-voted precision within a time budget per hypothesis; prints the table it explored and
// writes the best parameters for `detect --params` (host/tune/tune_run.hpp).
#include <cstdint>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "host/app/model_options.hpp"
#include "host/app/verbs.hpp"
#include "host/core/error.hpp"
#include "host/app/detect_options.hpp"
#include "host/tune/tune_run.hpp"

namespace binpick::cli {
namespace {

struct TuneArgs {
  ModelArgs model;
  pipeline::TuneOptions tune;
  pipeline::DetectCliOptions start;
  // Wide types, so a negative value reaches our range check.
  std::int64_t distance_steps = BP_PPF_DEFAULT_DIST_STEPS;
  std::int64_t angle_steps = BP_PPF_DEFAULT_ANGLE_STEPS;
};

std::uint32_t steps(std::int64_t value, const char* option, std::int64_t lo, std::int64_t hi) {
  if (value < lo || value > hi)
    throw InputError(fmt::format("{} {} must be in [{}, {}]", option, value, lo, hi));
  return static_cast<std::uint32_t>(value);
}

void run_tune(TuneArgs& a) {
  pipeline::TuneOptions o = a.tune;
  o.part = {a.model.model, model_options_of(a.model)};
  o.start.detect = pipeline::resolve(a.start);
  o.start.distance_steps = steps(a.distance_steps, "--distance-steps", 1, 1000);
  o.start.angle_steps = steps(a.angle_steps, "--angle-steps", 4, 360);
  pipeline::check(o);  // before the slow stages: bad options fail fast
  pipeline::run_tune(o, std::cout);
}

}  // namespace

void add_tune_verb(CLI::App& app) {
  auto a = std::make_shared<TuneArgs>();
  auto* verb = app.add_subcommand(
      "tune",
      "Choose the detection parameters automatically: on a small synthetic dataset, search the "
      "reference ratio, clustering thresholds, exclusion radius and the model's angle and "
      "distance steps for the best top-voted precision at (10 %, 15 deg) within a time budget "
      "per hypothesis. Prints the table explored; writes OUT/tune.csv, OUT/best.json (for "
      "`detect --params`) and OUT/best.ppfm (its model). Rerunning resumes.");
  add_model_options(verb, a->model);
  auto& o = a->tune;
  verb->add_option("--out", o.out,
                   "working directory: dataset/, models/, evals/, tune.csv, best.json, best.ppfm")
      ->required();
  verb->add_option("--bins", o.bins, "bins of the tuning dataset")->capture_default_str();
  verb->add_option("--objects", o.objects, "parts per bin")->capture_default_str();
  verb->add_option("--noise", o.noise,
                   "depth noise sigma of the tuning dataset, fraction of the diameter")
      ->capture_default_str();
  verb->add_option("--seed", o.seed, "random seed of the bins")->capture_default_str();
  verb->add_option("--width", o.width, "image width, pixels")->capture_default_str();
  verb->add_option("--height", o.height, "image height, pixels")->capture_default_str();
  verb->add_option("--max-wall-seconds", o.max_wall_seconds,
                   "wall-clock limit of one bin's physics (0: none)")
      ->capture_default_str();
  verb->add_option("--budget-ms", o.search.budget_ms,
                   "time per hypothesis allowed (ms, as eval measures it: the image's detection "
                   "time over its hypotheses)")
      ->capture_default_str();
  verb->add_option("--rounds", o.search.rounds,
                   "rounds of coordinate descent at most (each tries every value of every "
                   "parameter; stops early when a round finds nothing better)")
      ->capture_default_str();
  verb->add_option("--max-evals", o.search.max_evals, "parameter sets measured at most")
      ->capture_default_str();
  verb->add_option("--voxel-ratio", o.voxel_ratio,
                   "subsampling voxel of every model, fraction of the diameter (not searched)")
      ->capture_default_str();
  verb->add_option("--distance-steps", a->distance_steps, "starting point: model distance steps")
      ->capture_default_str();
  verb->add_option("--angle-steps", a->angle_steps, "starting point: model angle steps")
      ->capture_default_str();
  pipeline::add_detect_cli_options(verb, a->start, "starting point");
  verb->callback([a] { run_tune(*a); });
}

}  // namespace binpick::cli
