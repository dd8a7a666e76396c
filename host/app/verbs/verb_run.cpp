// `binpick run`: the paper's experiment in one command (section IV): a dataset per noise level,
// the model trained once, detection and evaluation of each, one report with a curve per noise
// level, and a final table. Every stage resumes, so the same command again finishes an
// interrupted run (host/tune/experiment.hpp).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "host/app/options/dataset_options.hpp"
#include "host/app/options/detect_options.hpp"
#include "host/app/options/model_options.hpp"
#include "host/app/options/train_options.hpp"
#include "host/app/options/scene_options.hpp"
#include "host/app/options/shard_options.hpp"
#include "host/shards/slurm_run.hpp"
#include "host/tune/experiment_shards.hpp"
#include "host/app/verbs/verbs.hpp"
#include "host/core/error.hpp"
#include "host/core/output_lock.hpp"
#include "host/tune/experiment.hpp"

namespace binpick::cli {
namespace {

struct RunArgs {
  ModelArgs model;
  ExperimentOptions experiment;
  DatasetArgs dataset;
  TrainArgs train;
  std::string noise = "0";
  DetectCliOptions detect;
  SceneArgs scene;
  ShardCliOptions shards;  // --shard K/N, --slurm
};

// The table, times and report of a finished experiment; for a shard whose batch is not
// finished, what is left to do.
std::string outcome(const ExperimentResult& r, const ExperimentOptions& o) {
  if (r.scenes_missing > 0)
    return fmt::format(
        "shard {} done; {} scenes of other shards still to detect: the shard that finishes last "
        "writes the report (or the same command without --shard)\n",
        o.shard.name(), r.scenes_missing);
  for (const auto& w : r.report.warnings) std::cerr << "binpick: warning: " << w << "\n";
  return fmt::format(
      "\n{}\ntime: synth {:.1f} s, train {:.1f} s{}, detect {:.1f} s, eval {:.1f} s\n"
      "report: {}\n",
      results_table(r.evaluations), r.synth_s, r.train_s, r.model_reused ? " (reused)" : "",
      r.detect_s, r.eval_s, r.report.html.string());
}

void run_run(RunArgs& a) {
  ExperimentOptions o = a.experiment;
  // Parsed here rather than by CLI11, which would quietly keep the default for "--noise ''".
  o.noise = parse_noise_list(a.noise);
  o.part = part_spec_of(a.model);
  apply_dataset_args(a.dataset, o);
  o.max_wall_seconds = a.dataset.max_wall_seconds;
  o.train = train_params_of(a.train);
  o.detect = resolve(a.detect);
  apply_scene_args(a.scene, o.scene);
  o.shard = shard_of(a.shards);
  check(o);  // before the slow stages: bad options fail fast
  const auto experiment = [&o] {
    std::vector<Model> distractors;
    for (const DistractorSpec& d : o.scene.distractors)
      distractors.push_back(load_part_finding_symmetries({d.model, {}}));
    const Model part = load_part_finding_symmetries(o.part);
    // After the inputs load (a typo writes nothing); a shard shares it with the other shards.
    const OutputLock lock = OutputLock::directory(o.out, o.shard.index, o.shard.count);
    return run_experiment(part, o, std::cout, distractors);
  };
  if (a.shards.slurm.enabled) {
    // The merge is the experiment in this process: every bin is there, so it only evaluates.
    const ShardedBatch batch{experiment_state_dir(o),
                             experiment_shard_record(o, a.shards.slurm.tasks),
                             [&o](int bin) { return experiment_bin_done(o, bin); },
                             [&] { return outcome(experiment(), o); }};
    return run_on_slurm(batch, a.shards.slurm, task_command(own_command_line()), std::cout);
  }
  if (o.shard.sharded()) claim_experiment_shards(o);
  std::cout << outcome(experiment(), o);
}

}  // namespace

void add_run_verb(CLI::App& app) {
  auto a = std::make_shared<RunArgs>();
  auto* verb = app.add_subcommand(
      "run",
      "The paper's experiment in one command: synthesise a dataset per noise level, train the "
      "model once, detect and evaluate each dataset, write one report (a curve per noise level) "
      "and print a table. Rerunning the same command resumes.");
  add_model_options(verb, a->model);
  auto& o = a->experiment;
  verb->add_option("--out", o.out,
                   "working directory: noise_S/ datasets, model.ppfm, results/, report/")
      ->required();
  add_dataset_options(verb, a->dataset, "bins per noise level");
  add_scene_options(verb, a->scene);
  verb->add_option("--noise", a->noise,
                   "noise levels, comma separated: Gaussian depth noise sigma as a fraction of the "
                   "diameter (the paper: 0,0.01,0.02,0.03,0.04,0.05)")
      ->capture_default_str();
  add_train_options(verb, a->train, "training");
  verb->add_option("--pictures", o.pictures, "images pictured per noise level in the report")
      ->capture_default_str();
  add_detect_cli_options(verb, a->detect, "detection");
  add_shard_options(verb, a->shards, "bins (each shard makes and detects its bins at every noise level)");
  verb->callback([a] { run_run(*a); });
}

}  // namespace binpick::cli
