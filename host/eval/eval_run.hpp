// `binpick eval` as a library call: evaluate one or more (dataset, results) pairs, then write the
// report directory. All inputs are read and checked before anything is written, so bad input
// never leaves a half-written report.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "host/eval/metrics/bop_scores.hpp"
#include "host/eval/metrics/evaluate.hpp"
#include "host/eval/metrics/pick_success.hpp"
#include "host/eval/metrics/precision_curves.hpp"

namespace binpick::eval {

struct EvalInput {
  std::filesystem::path dataset, results;
  DatasetLayout layout;
};

struct DatasetEvaluation {
  Dataset dataset;
  std::filesystem::path results;
  EvalSummary summary;
  std::array<PrecisionCurve, 4> curves;  // figure7_curves(summary.results)
  ScoreCurve score_curve;                 // score_curve(summary.results, options.loose)
  BopScores bop;                          // BOP's MSSD / MSPD recalls, next to the paper's
  std::vector<ObjectSummary> objects;     // the paper's figures per obj_id, when several
  std::optional<PickSummary> picks;       // with RESULTS.picks.csv beside the results
};

// Loads and evaluates each pair; InputError names the failing pair. With every dataset's noise
// known, the evaluations come back sorted by noise (the curves' colour order), else as given.
std::vector<DatasetEvaluation> evaluate_inputs(const std::vector<EvalInput>& inputs,
                                               const EvalOptions& options = {});

struct ReportOptions {
  std::filesystem::path out;  // created if missing
  int pictures = 3;           // images pictured per dataset
  EvalOptions eval;
};

struct ReportFiles {
  std::filesystem::path html, json, curves_csv, score_curves_csv, hypotheses_csv;
  std::filesystem::path plot;        // precision.png; empty if gnuplot was not available or failed
  std::filesystem::path score_plot;  // score_threshold.png; empty likewise, or if no dataset's
                                     // scores are in [0, 1]
  std::vector<std::string> warnings;
};

// Writes report.html, report.json, curves.csv, score_curves.csv, hypotheses.csv, precision.png,
// score_threshold.png and pictures/*.png into options.out, each atomically, report.html last.
// Results whose scores are outside [0, 1] get a warning (score_range_warning), not an error.
ReportFiles write_report(const std::vector<DatasetEvaluation>& evaluations,
                         const ReportOptions& options);

}  // namespace binpick::eval
