// The machine-readable parts of the report: report.json (the key numbers, for `binpick tune` and
// scripts) and hypotheses.csv (every hypothesis with its match and errors).
#pragma once

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/eval/eval_run.hpp"

namespace binpick::eval {

// {"operating_points": {...}, "datasets": [{label, dataset, results, noise, images, ...,
// "precision": {"loose": {"translation_pct", "rotation_deg", "all", "top"}, "strict": {...}},
// "median": {...}, "ms_per_hypothesis", "score_calibration": {"keep", "scores_outside_unit",
// "max_score", "loose": {"any_right", "right", "threshold", "accepted", "accepted_right",
// "accepted_wrong", "kept", "wrong_fraction"}, "strict": {...}}, "bop": {...}, and with
// results of several obj_ids "objects": [{"obj_id", images, ..., "score_calibration"}]: the same
// figures per obj_id}]} (score_calibration.hpp; "bop": bop_report.hpp).
// Non-finite numbers (no data) are null.
nlohmann::json report_json(const std::vector<DatasetEvaluation>& evaluations,
                           const EvalOptions& options);
void write_report_json(const std::filesystem::path& path,
                       const std::vector<DatasetEvaluation>& evaluations, const EvalOptions& options);

// label,scene_id,im_id,rank,obj_id,score,top,gt_index,translation_mm,translation_pct,
// rotation_deg,ms,landing (errors "inf" when the image has no part of that obj_id; landing: part,
// distractor or none, evaluate.hpp).
void write_hypotheses_csv(const std::filesystem::path& path,
                          const std::vector<DatasetEvaluation>& evaluations);

}  // namespace binpick::eval
