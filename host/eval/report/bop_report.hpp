// BOP's recalls in the report, next to the paper's figures: the "bop" object of report.json,
// the HTML section and the lines `binpick eval` prints.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/eval/eval_run.hpp"

namespace binpick::eval {

// {"ar", "ar_mssd", "ar_mspd", "ar_vsd": null, "targets", "estimates", "targets_source",
//  "vertices", "image_width", "image_width_known", "mssd": {"thresholds", "recall"},
//  "mspd": {...}, "objects": [{"obj_id", "targets", "ar_mssd", "ar_mspd", "mssd_recall",
//  "mspd_recall"}]}, or {"unavailable": "no .../obj_000001.ply"} without the model.
nlohmann::json bop_json(const BopScores& scores);

// <h2> section with a table of AR per dataset and per obj_id.
std::string bop_html_section(const std::vector<DatasetEvaluation>& evaluations);

// One line per dataset (and per obj_id when it has several): "LABEL  BOP AR_MSSD 0.812 ...".
std::string bop_summary_lines(const std::vector<DatasetEvaluation>& evaluations);

}  // namespace binpick::eval
