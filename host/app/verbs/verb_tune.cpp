// `binpick tune`: chooses detection parameters automatically (paper III-D: the whole loop is
// automatic, so it can tune itself). Searches reference ratio, clustering thresholds, exclusion
// radius and the model's angle and distance steps on a small synthetic dataset, maximising
// top-voted precision within a time budget per hypothesis; prints the table it explored and
// writes the best parameters for `detect --params` (host/tune/tune_run.hpp).
#include <CLI/CLI.hpp>
#include <cstdint>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "host/app/options/dataset_options.hpp"
#include "host/app/options/detect_options.hpp"
#include "host/app/options/model_options.hpp"
#include "host/app/options/shard_options.hpp"
#include "host/app/options/train_options.hpp"
#include "host/app/verbs/verbs.hpp"
#include "host/core/error.hpp"
#include "host/core/output_lock.hpp"
#include "host/tune/tune_run.hpp"
#include "host/tune/tune_slurm.hpp"

namespace binpick::cli {
namespace {

struct TuneArgs {
  ModelArgs model;
  TuneOptions tune;
  DatasetArgs dataset{.bins = TuneOptions{}.bins,
                      .objects = TuneOptions{}.objects};
  TrainArgs train;
  DetectCliOptions start;
  ShardCliOptions shards;        // --slurm; --shard with --points (a --slurm task)
  std::filesystem::path points;  // --points FILE
};

void run_tune(TuneArgs& a) {
  TuneOptions o = a.tune;
  o.part = part_spec_of(a.model);
  apply_dataset_args(a.dataset, o);
  o.max_wall_seconds = a.dataset.max_wall_seconds;
  const PpfTrainParams train = train_params_of(a.train);
  o.voxel_ratio = train.voxel_ratio;
  o.start.distance_steps = train.distance_steps;
  o.start.angle_steps = train.angle_steps;
  o.start.detect = resolve(a.start);
  check(o);  // before the slow stages: bad options fail fast
  const Shard shard = shard_of(a.shards);
  if (shard.sharded() && a.points.empty())
    throw InputError("tune --shard K/N measures a share of --points FILE (what a tune --slurm "
                     "task does); without it, use --slurm");
  const Model part = load_part_finding_symmetries(o.part);
  if (a.shards.slurm.enabled)
    return run_tune_on_slurm(part, o, a.shards.slurm, task_command(own_command_line()), std::cout);
  // After the inputs load: a typo writes nothing.
  const OutputLock lock = OutputLock::directory(o.out, shard.index, shard.count);
  if (!a.points.empty()) return measure_candidates(part, o, a.points, shard, std::cout);
  binpick::run_tune(part, o, std::cout);
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
      "`detect --params`) and OUT/best.ppfm (its model). Rerunning resumes. With --slurm the "
      "candidates of each round are measured by a Slurm job array.");
  add_model_options(verb, a->model);
  auto& o = a->tune;
  verb->add_option("--out", o.out,
                   "working directory: dataset/, models/, evals/, tune.csv, best.json, best.ppfm")
      ->required();
  add_dataset_options(verb, a->dataset, "bins of the tuning dataset");
  verb->add_option("--noise", o.noise,
                   "depth noise sigma of the tuning dataset, fraction of the diameter")
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
  add_train_options(verb, a->train,
                    "models (the voxel is kept; the steps are the search's starting point)");
  // The starting point's robot-mode parameters are not options: tune measures every hypothesis,
  // and its --budget-ms (per hypothesis) is the search's own. Nor is a cell's bin pose: tune's
  // bins are its own synthetic ones.
  add_detect_cli_options(verb, a->start, "starting point",
                         {"budget-ms", "stop-at-confident", "bin-pose"});
  add_shard_options(verb, a->shards, "points");
  // The generic texts speak of merging outputs; tune's shards and array measure points.
  verb->get_option("--shard")->description(
      "K/N: with --points, measure only the points at positions K-1, K-1+N, ... of the file (what "
      "task K of a --slurm array runs)");
  verb->get_option("--slurm")->description(
      "measure each round's candidates as a Slurm job array of --tasks tasks (script and logs in "
      "OUT/shards/points-HASH/slurm/), follow it, then replay the search over the results; print "
      "the table and write the files as without --slurm; run again to resubmit only what is "
      "missing");
  verb->add_option("--points", a->points,
                   "measure only the points of this file (OUT/shards/points-HASH.json, "
                   "written by --slurm for its array tasks) into OUT/evals/")
      ->excludes("--slurm");
  verb->callback([a] { run_tune(*a); });
}

}  // namespace binpick::cli
