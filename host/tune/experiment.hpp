// The paper's experiment as one call (`binpick run`, `binpick demo`): for each noise level a
// synthetic dataset, one model trained once, detection of every dataset and one report with a
// curve per noise level. Every stage resumes: synth keeps whole bins, the model is reused when
// its inputs match (model_store), detection keeps finished scenes; the report is rewritten.
//
//   OUT/noise_0.00/            dataset (BOP) per noise level
//   OUT/model.ppfm (+ .json)   the trained model and what it was trained from
//   OUT/results/noise_0.00.csv detection results (BOP results CSV), the file detection resumes
//   OUT/results/binpick_noise000-test.csv  the same rows named as the BOP toolkit parses a
//                              results file (METHOD_DATASET-SPLIT.csv), rewritten every run
//   OUT/bop/noise000 -> ../noise_0.00      the dataset under that name (a symlink), for the
//                              toolkit's datasets_path
//   OUT/report/                report.html, report.json, curves.csv, score_curves.csv,
//                              precision.png, score_threshold.png, pictures/
#pragma once

#include "synth/synthesize.hpp"

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "host/detect/detector.hpp"
#include "host/eval/eval_run.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/model_store.hpp"

namespace binpick {

struct ExperimentOptions {
  PartSpec part;
  std::filesystem::path out;
  std::vector<double> noise{0.0};  // sigma as a fraction of the diameter, one dataset each
  int bins = 30;
  int objects = 350;
  std::uint64_t seed = 1;
  std::uint32_t width = 1600, height = 900;
  double max_wall_seconds = 0;     // per bin's physics, 0 = unlimited
  PpfTrainParams train;
  DetectParams detect;
  int pictures = 3;                // images pictured per dataset in the report
  // What the bins look like beyond the paper's (the bin rendered, distractors, camera tilt,
  // sensor model): each dataset's synth options start from these.
  SynthOptions scene;
  // --shard K/N: bins K-1, K-1+N, ... of every level are made and detected here; the report is
  // written by the shard that finds every level's scenes done.
  Shard shard;
};

// Throws InputError (naming the option) for an empty or out-of-range noise list, two noise
// levels that would share a directory, bad counts, or bad train/detect parameters.
void check(const ExperimentOptions& options);

// "0,0.01,0.02" -> the levels. InputError for an empty list or item, or an item that is not a
// number (range checks are check(ExperimentOptions)).
std::vector<double> parse_noise_list(const std::string& text);

// The same for any comma-separated list of numbers given to `option` (messages name it and
// show `example`).
std::vector<double> parse_number_list(const std::string& text, const std::string& option,
                                      const std::string& example);

// "noise_0.00": two decimals, more when the level needs them (0.005 -> noise_0.005).
std::string noise_dir_name(double noise);

// The level's dataset name for the BOP toolkit: noise_dir_name's digits without the point
// ("noise000" for 0, "noise002" for 0.02, "noise0005" for 0.005, "noise100" for 1). The toolkit
// splits a results file name at '_', '-' and '.', so the name holds none of them; levels with
// distinct directories get distinct names (the point always follows the first digit).
std::string bop_dataset_name(double noise);

// "binpick_noise002-test.csv": METHOD_DATASET-SPLIT.csv with method binpick and split test.
std::string toolkit_results_name(double noise);

struct ExperimentResult {
  std::vector<eval::DatasetEvaluation> evaluations;  // by noise
  eval::ReportFiles report;
  std::filesystem::path model;
  int bins_made = 0, bins_reused = 0;
  bool model_reused = false;
  double synth_s = 0, train_s = 0, detect_s = 0, eval_s = 0;
  std::size_t scenes_missing = 0;  // of other shards, over every level: no report yet
};

// OUT/results/noise_S.csv: a level's detection results.
std::filesystem::path experiment_results_csv(const ExperimentOptions& o, double noise);

// Runs every stage on `part` (loaded from options.part), writing one line per stage and dataset
// to `log` (the stages' progress bars go to stderr). `distractors`: the models of
// options.scene.distractors, in order.
ExperimentResult run_experiment(const Model& part, const ExperimentOptions& options,
                                std::ostream& log, const std::vector<Model>& distractors = {});

// The final table: noise, bins, hypotheses, precision top/all at both operating points, the
// wrong fraction at the score threshold keeping 90 % of right poses (loose point), ms per
// hypothesis; one row per evaluation.
std::string results_table(const std::vector<eval::DatasetEvaluation>& evaluations,
                          const eval::EvalOptions& at = {});

}  // namespace binpick
