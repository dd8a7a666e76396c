// `binpick eval` as a library call: evaluate one or more (dataset, results) pairs, then write the
// report directory. All inputs are read and checked before anything is written, so bad input
// never leaves a half-written report.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "host/eval/metrics/evaluate.hpp"
#include "host/eval/metrics/precision_curves.hpp"

namespace binpick::eval {

struct EvalInput {
  std::filesystem::path dataset, results;
};

struct DatasetEvaluation {
  Dataset dataset;
  std::filesystem::path results;
  EvalSummary summary;
  std::array<PrecisionCurve, 4> curves;  // figure7_curves(summary.results)
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
  std::filesystem::path html, json, curves_csv, hypotheses_csv;
  std::filesystem::path plot;   // empty if gnuplot was not available or failed
  std::vector<std::string> warnings;
};

// Writes report.html, report.json, curves.csv, hypotheses.csv, precision.png and pictures/*.png
// into options.out, each atomically, report.html last.
ReportFiles write_report(const std::vector<DatasetEvaluation>& evaluations,
                         const ReportOptions& options);

}  // namespace binpick::eval
