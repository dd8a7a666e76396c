// `binpick tune` as a library call: the closed loop of the paper (section III-D) over a small
// synthetic dataset. Makes the dataset, then searches (tune_search) measuring each point by
// detecting every bin and evaluating: precision of the top-voted hypothesis at (10 %, 15 deg)
// under a budget of time per hypothesis. Resumable: everything lands in OUT and is reused.
//
//   OUT/dataset/            the bins (synth resumes them)
//   OUT/models/dD_aA.ppfm   one model per (distance steps D, angle steps A), trained once
//   OUT/evals/KEY.csv       the results of each point measured (a rerun only re-reads them)
//   OUT/tune.csv            the table explored
//   OUT/best.json           the best detection parameters (detect --params)
//   OUT/best.ppfm           the model of the best point (its steps may differ from train's
//                           defaults: detect with this model or retrain with best-train.json)
//   OUT/best-train.json     the training parameters of best.ppfm
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>

#include "host/train/model_store.hpp"
#include "host/tune/tune_search.hpp"

namespace binpick {

struct TuneOptions {
  PartSpec part;
  std::filesystem::path out;
  int bins = 4;
  int objects = 70;
  double noise = 0;
  std::uint64_t seed = 1;
  std::uint32_t width = 1600, height = 900;
  double max_wall_seconds = 0;  // per bin's physics, 0 = unlimited
  double voxel_ratio = 0.05;    // of every model trained (not searched)
  TunePoint start;              // the paper's parameters unless --params says otherwise
  SearchOptions search;
};

// InputError naming the option for anything no tune can run with.
void check(const TuneOptions& options);

struct TuneResult {
  SearchResult search;
  TunePoint best;
  std::filesystem::path table_csv, best_json, best_model, best_train_json;
};

// Runs the loop, printing the table to `out` as it goes (header, one row per measurement, then
// the best); a progress bar over the measurements on stderr.
// `part` is the model options.part names, loaded.
TuneResult run_tune(const Model& part, const TuneOptions& options, std::ostream& out);

// The stages of run_tune, for `tune --slurm` (tune_slurm.hpp), which measures elsewhere:
// OUT/dataset made (or resumed), a line about it to `out`;
void make_tune_dataset(const Model& part, const TuneOptions& options, std::ostream& out);
// the search with `measure`, its table printed and OUT/tune.csv, best.json, best.ppfm and
// best-train.json written.
TuneResult search_and_report(const TuneOptions& options, class TuneMeasurer& measure,
                             std::ostream& out);

}  // namespace binpick
