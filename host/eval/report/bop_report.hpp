// BOP's recalls in the report, next to the paper's figures: the "bop" object of report.json,
// the HTML section and the lines `binpick eval` prints.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/eval/eval_run.hpp"

namespace binpick::eval {

// {"ar", "ar_vsd" (null without VSD), "ar_mssd", "ar_mspd", "targets", "estimates",
//  "targets_source", "vertices", "image_width", "image_width_known",
//  "mssd": {"thresholds", "recall"}, "mspd": {...}, "vsd": {"delta_mm", "taus", "thresholds",
//  "recall" [tau][threshold], "renders", "pairs_compared", "pairs_skipped"} (or
//  {"unavailable": why}, or null when not asked for), "objects": [{"obj_id", "targets", "ar_vsd",
//  "ar_mssd", "ar_mspd", "mssd_recall", "mspd_recall"}]}, or {"unavailable": "no
//  .../obj_000001.ply"} without the model.
nlohmann::json bop_json(const BopScores& scores);

// <h2> section with a table of AR per dataset and per obj_id.
std::string bop_html_section(const std::vector<DatasetEvaluation>& evaluations);

// One line per dataset (and per obj_id when it has several): "LABEL  BOP: AR_VSD 0.790 ...".
std::string bop_summary_lines(const std::vector<DatasetEvaluation>& evaluations);

}  // namespace binpick::eval
