#include "host/eval/report/report_tables.hpp"

#include "host/core/csv_quote.hpp"

#include <cmath>

#include <fmt/format.h>

#include "host/core/atomic_file.hpp"
#include "host/eval/report/bop_report.hpp"

namespace binpick::eval {
namespace {

using nlohmann::json;

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json operating_point(const PrecisionAt& p) {
  return {{"translation_pct", p.at.translation_pct}, {"rotation_deg", p.at.rotation_deg},
          {"all", p.all}, {"top", p.top}};
}

json calibration(const ScoreCalibration& c) {
  return {{"any_right", c.any_right},
          {"right", c.right},
          {"threshold", number(c.threshold)},
          {"accepted", c.accepted},
          {"accepted_right", c.accepted_right},
          {"accepted_wrong", c.accepted_wrong},
          {"kept", number(c.kept)},
          {"wrong_fraction", number(c.wrong_fraction)}};
}

// The paper's figures of a summary (of a dataset, or of one obj_id's rows).
json figures_json(const EvalSummary& s) {
  return {{"images", s.images},
          {"images_with_results", s.images_with_results},
          {"hypotheses", s.hypotheses},
          {"unmatched", s.unmatched},
          {"landing",
           {{"all_on_nothing", s.all_on_nothing},
            {"all_on_distractor", s.all_on_distractor},
            {"top_on_nothing", s.top_on_nothing},
            {"top_on_distractor", s.top_on_distractor}}},
          {"precision", {{"loose", operating_point(s.loose)}, {"strict", operating_point(s.strict)}}},
          {"median",
           {{"translation_pct_all", number(s.median_translation_pct_all)},
            {"rotation_deg_all", number(s.median_rotation_deg_all)},
            {"translation_pct_top", number(s.median_translation_pct_top)},
            {"rotation_deg_top", number(s.median_rotation_deg_top)}}},
          {"ms_per_hypothesis", number(s.ms_per_hypothesis)},
          {"score_calibration",
           {{"keep", s.score_loose.keep},
            {"scores_outside_unit", s.score_loose.outside_unit},
            {"max_score", number(s.score_loose.max_score)},
            {"loose", calibration(s.score_loose)},
            {"strict", calibration(s.score_strict)}}}};
}

json summary_json(const DatasetEvaluation& e) {
  json j = figures_json(e.summary);
  j["label"] = e.dataset.label;
  j["dataset"] = e.dataset.root.string();
  j["results"] = e.results.string();
  j["noise"] = e.dataset.noise >= 0 ? json(e.dataset.noise) : json(nullptr);
  j["bop"] = bop_json(e.bop);
  if (e.picks) {
    json firsts = json::array();
    for (const PickOutcome& o : e.picks->firsts)
      firsts.push_back({{"scene_id", o.pick.scene_id}, {"im_id", o.pick.im_id}, {"obj_id", o.pick.obj_id},
                        {"right", o.right}, {"on_grasp", o.on_grasp},
                        {"collision", o.collision}, {"success", o.success()}});
    j["picks"] = {{"images", e.picks->images}, {"picked", e.picks->picked},
                  {"success", e.picks->success}, {"rate", e.picks->rate()},
                  {"first_picks", std::move(firsts)}};
  }
  if (!e.objects.empty()) {
    json objects = json::array();
    for (const ObjectSummary& o : e.objects) {
      json figures = figures_json(o.summary);
      figures["obj_id"] = o.obj_id;
      objects.push_back(std::move(figures));
    }
    j["objects"] = std::move(objects);
  }
  return j;
}

const char* landing_name(Landing l) {
  return l == Landing::part ? "part" : l == Landing::distractor ? "distractor" : "none";
}

}  // namespace

json report_json(const std::vector<DatasetEvaluation>& evaluations, const EvalOptions& options) {
  json datasets = json::array();
  for (const auto& e : evaluations) datasets.push_back(summary_json(e));
  return {{"operating_points",
           {{"loose", {{"translation_pct", options.loose.translation_pct},
                       {"rotation_deg", options.loose.rotation_deg}}},
            {"strict", {{"translation_pct", options.strict.translation_pct},
                        {"rotation_deg", options.strict.rotation_deg}}}}},
          {"datasets", datasets}};
}

void write_report_json(const std::filesystem::path& path,
                       const std::vector<DatasetEvaluation>& evaluations, const EvalOptions& options) {
  const std::string text = report_json(evaluations, options).dump(2) + "\n";
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

void write_hypotheses_csv(const std::filesystem::path& path,
                          const std::vector<DatasetEvaluation>& evaluations) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "label,scene_id,im_id,rank,obj_id,score,top,gt_index,translation_mm,translation_pct,"
           "rotation_deg,ms,landing\n";
    for (const auto& e : evaluations) {
      const std::string label = csv_quoted(e.dataset.label);
      for (const auto& r : e.summary.results)
        out << fmt::format("{},{},{},{},{},{:g},{},{},{:.4f},{:.4f},{:.4f},{:.3f},{}\n", label,
                           r.scene_id, r.im_id, r.rank, r.obj_id, r.score, r.top ? 1 : 0,
                           r.gt_index, r.translation_mm, r.translation_pct, r.rotation_deg, r.ms,
                           landing_name(r.landing));
    }
  });
}

}  // namespace binpick::eval
