#include "host/eval/report/bop_report.hpp"

#include <cmath>

#include <fmt/format.h>

#include "host/eval/report/report_html.hpp"

namespace binpick::eval {
namespace {

using nlohmann::json;

json curve_json(const RecallCurve& c) {
  return {{"thresholds", c.thresholds}, {"recall", c.recall}};
}

// The obj_id's curve of a metric (both metrics list the same objects in the same order).
const RecallCurve& object_curve(const MetricRecall& m, std::size_t i) { return m.objects[i].curve; }

// AR_VSD of the whole dataset (i = npos) or of its i-th obj_id; NaN without VSD.
double vsd_average(const BopScores& s, std::size_t i = std::string::npos) {
  if (!s.has_vsd) return std::nan("");
  return i == std::string::npos ? s.vsd.average : object_vsd_average(s.vsd, i);
}

// BOP's AR: the mean of the three recalls, or of MSSD and MSPD without VSD.
double average(double vsd, double mssd, double mspd) {
  return std::isnan(vsd) ? (mssd + mspd) / 2.0 : (vsd + mssd + mspd) / 3.0;
}

std::string ar_cells(double vsd, double mssd, double mspd) {
  const std::string v = std::isnan(vsd) ? "-" : fmt::format("{:.3f}", vsd);
  return fmt::format("<td>{}</td><td>{:.3f}</td><td>{:.3f}</td><td>{:.3f}</td>", v, mssd, mspd,
                     average(vsd, mssd, mspd));
}

json number_or_null(double x) { return std::isnan(x) ? json(nullptr) : json(x); }

json vsd_json(const BopScores& s) {
  if (!s.has_vsd)
    return s.vsd.unavailable.empty() ? json(nullptr) : json{{"unavailable", s.vsd.unavailable}};
  json recall = json::array();
  for (const auto& m : s.vsd.by_tau) recall.push_back(m.overall.recall);
  return {{"delta_mm", s.vsd.delta_mm},
          {"taus", s.vsd.taus},
          {"thresholds", bop_vsd_thresholds()},
          {"recall", recall},  // [tau][threshold]
          {"renders", s.vsd.renders},
          {"pairs_compared", s.vsd.pairs_compared},
          {"pairs_skipped", s.vsd.pairs_skipped}};
}

}  // namespace

json bop_json(const BopScores& s) {
  if (!s.unavailable.empty()) return {{"unavailable", s.unavailable}};
  json objects = json::array();
  for (std::size_t i = 0; i < s.mssd.objects.size(); ++i)
    objects.push_back({{"obj_id", s.mssd.objects[i].obj_id},
                       {"targets", s.mssd.objects[i].targets},
                       {"ar_vsd", number_or_null(vsd_average(s, i))},
                       {"ar_mssd", object_curve(s.mssd, i).average},
                       {"ar_mspd", object_curve(s.mspd, i).average},
                       {"mssd_recall", object_curve(s.mssd, i).recall},
                       {"mspd_recall", object_curve(s.mspd, i).recall}});
  return {{"ar", s.average_recall},
          {"ar_mssd", s.mssd.overall.average},
          {"ar_mspd", s.mspd.overall.average},
          {"ar_vsd", number_or_null(vsd_average(s))},
          {"targets", s.targets},
          {"estimates", s.estimates},
          {"targets_source", s.targets_source},
          {"vertices", s.vertices.filename().string()},  // models_eval or models
          {"image_width", s.image_width},
          {"image_width_known", s.image_width_known},
          {"mssd", curve_json(s.mssd.overall)},
          {"mspd", curve_json(s.mspd.overall)},
          {"vsd", vsd_json(s)},
          {"objects", objects}};
}

std::string bop_html_section(const std::vector<DatasetEvaluation>& evaluations) {
  std::string s =
      "<h2>BOP average recall</h2>\n<p>BOP Challenge 2019 scores (bop_toolkit): MSSD, the "
      "largest distance of a model vertex between the estimate and the nearest symmetric copy "
      "of the ground truth, is right below 0.05, 0.10, ... 0.50 of the diameter; MSPD, the same "
      "in the image, below 5, 10, ... 50 px (for a 640 px wide image). Each estimate, by score, "
      "takes the unmatched target with the smallest error below the threshold; recall = matched "
      "targets / targets (instances with visib_fract &ge; 0.1, or test_targets_bop19.json), "
      "counting at most inst_count estimates per image and object; AR = mean recall over the "
      "thresholds. VSD compares the visible surface of the model rendered at the estimate and "
      "at the ground truth (distances from the camera, visibility tolerance 15 mm): right below "
      "0.05, 0.10, ... 0.50, at each misalignment tolerance 0.05, 0.10, ... 0.50 of the "
      "diameter. AR is the mean of AR<sub>VSD</sub>, AR<sub>MSSD</sub> and AR<sub>MSPD</sub>, "
      "as BOP's; where VSD is not computed (-), of the other two.</p>\n<table>\n<tr>"
      "<th>dataset</th><th>obj_id</th><th>targets</th><th>AR<sub>VSD</sub></th>"
      "<th>AR<sub>MSSD</sub></th><th>AR<sub>MSPD</sub></th><th>AR</th></tr>\n";
  for (const auto& e : evaluations) {
    const BopScores& b = e.bop;
    if (!b.unavailable.empty()) {
      s += fmt::format("<tr><td>{}</td><td colspan=\"6\">not scored: {}</td></tr>\n",
                       html_escaped(e.dataset.label), html_escaped(b.unavailable));
      continue;
    }
    s += fmt::format("<tr><td>{}</td><td>all</td><td>{}</td>{}</tr>\n",
                     html_escaped(e.dataset.label), b.targets,
                     ar_cells(vsd_average(b), b.mssd.overall.average, b.mspd.overall.average));
    if (b.mssd.objects.size() > 1)
      for (std::size_t i = 0; i < b.mssd.objects.size(); ++i)
        s += fmt::format("<tr><td></td><td>{}</td><td>{}</td>{}</tr>\n", b.mssd.objects[i].obj_id,
                         b.mssd.objects[i].targets,
                         ar_cells(vsd_average(b, i), object_curve(b.mssd, i).average,
                                  object_curve(b.mspd, i).average));
  }
  return s + "</table>\n";
}

std::string bop_summary_lines(const std::vector<DatasetEvaluation>& evaluations) {
  std::string s;
  for (const auto& e : evaluations) {
    const BopScores& b = e.bop;
    if (!b.unavailable.empty()) {
      s += fmt::format("{:<24} BOP: not scored ({})\n", e.dataset.label, b.unavailable);
      continue;
    }
    if (b.has_vsd)
      s += fmt::format("{:<24} BOP: AR_VSD {:.3f}  AR_MSSD {:.3f}  AR_MSPD {:.3f}  AR {:.3f}  "
                       "({} targets, {} estimates; VSD rendered {} models in {:.1f} s, compared "
                       "in {:.1f} s)\n",
                       e.dataset.label, b.vsd.average, b.mssd.overall.average,
                       b.mspd.overall.average, b.average_recall, b.targets, b.estimates,
                       b.vsd.renders, b.vsd.render_ms / 1e3, b.vsd.compare_ms / 1e3);
    else
      s += fmt::format("{:<24} BOP: AR_MSSD {:.3f}  AR_MSPD {:.3f}  AR(MSSD,MSPD) {:.3f}  "
                       "({} targets, {} estimates; no VSD{})\n",
                       e.dataset.label, b.mssd.overall.average, b.mspd.overall.average,
                       b.average_recall, b.targets, b.estimates,
                       b.vsd.unavailable.empty() ? "" : ": " + b.vsd.unavailable);
    if (b.mssd.objects.size() > 1)
      for (std::size_t i = 0; i < b.mssd.objects.size(); ++i)
        s += fmt::format("{:<24}   obj_id {}: {}AR_MSSD {:.3f}  AR_MSPD {:.3f}  ({} targets)\n", "",
                         b.mssd.objects[i].obj_id,
                         b.has_vsd ? fmt::format("AR_VSD {:.3f}  ", vsd_average(b, i)) : "",
                         object_curve(b.mssd, i).average, object_curve(b.mspd, i).average,
                         b.mssd.objects[i].targets);
  }
  return s;
}

}  // namespace binpick::eval
