#include "host/eval/report/report_html.hpp"

#include <cmath>

#include <fmt/format.h>

#include "host/eval/report/bop_report.hpp"
#include "host/eval/report/colormap.hpp"
#include "host/core/atomic_file.hpp"

namespace binpick::eval {
namespace {

constexpr const char* kStyle = R"(<style>
body { font-family: 'DejaVu Sans', Arial, sans-serif; margin: 24px auto; max-width: 1500px; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.6em; } h3 { font-size: 1.0em; }
table { border-collapse: collapse; margin: 8px 0; }
th, td { border: 1px solid #bbb; padding: 4px 9px; text-align: right; }
th { background: #eee; } td:first-child, th:first-child { text-align: left; }
figure { display: inline-block; margin: 6px; vertical-align: top; }
figure img { max-width: 720px; width: 100%; border: 1px solid #999; }
figcaption { font-size: 0.85em; color: #444; max-width: 720px; }
.swatch { display: inline-block; width: 0.9em; height: 0.9em; vertical-align: middle; border: 1px solid #555; }
.warn { color: #a00; }
</style>
)";

std::string pct(double fraction) { return fmt::format("{:.1f} %", 100.0 * fraction); }
std::string num(double v, const char* unit) {
  return std::isfinite(v) ? fmt::format("{:.2f}{}", v, unit) : std::string("&ndash;");
}
std::string swatch(const Rgb& c) {
  return fmt::format("<span class=\"swatch\" style=\"background:{}\"></span>", hex(c));
}

std::string op(const OperatingPoint& p) {
  return fmt::format("({:g} %, {:g}&deg;)", p.translation_pct, p.rotation_deg);
}

// The calibrated threshold, or why there is none; flagged when the scores are not in [0, 1].
std::string threshold_cell(const ScoreCalibration& c) {
  if (!c.any_right) return "&ndash; (no right pose)";
  std::string s = threshold_text(c.threshold);
  if (c.outside_unit) s += " <span class=\"warn\">(scores not in [0, 1])</span>";
  return s;
}

std::string wrong_cell(const ScoreCalibration& c) {
  if (!c.any_right) return "&ndash;";
  return fmt::format("{} ({} of {})", pct(c.wrong_fraction), c.accepted_wrong, c.accepted);
}

// One row of the summary table: `label` (HTML) and its figures.
std::string summary_row(const std::string& label, const EvalSummary& m) {
  return fmt::format(
      "<tr><td>{}</td><td>{} ({} with results)</td><td>{}{}</td><td>{}</td><td>{}</td><td>{}</td>"
      "<td>{}</td><td>{} / {}</td><td>{} / {}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
      label, m.images, m.images_with_results, m.hypotheses,
      m.unmatched ? fmt::format(" ({} unmatched)", m.unmatched) : "", pct(m.loose.top),
      pct(m.loose.all), pct(m.strict.top), pct(m.strict.all), num(m.median_translation_pct_top, ""),
      num(m.median_translation_pct_all, ""), num(m.median_rotation_deg_top, ""),
      num(m.median_rotation_deg_all, ""), num(m.ms_per_hypothesis, " ms"),
      threshold_cell(m.score_loose), wrong_cell(m.score_loose));
}

std::string summary_table(const std::vector<DatasetEvaluation>& evaluations, const EvalOptions& o) {
  std::string s = fmt::format(
      "<table>\n<tr><th>dataset</th><th>images</th><th>hypotheses</th>"
      "<th>precision top<br>{0}</th><th>precision all<br>{0}</th>"
      "<th>precision top<br>{1}</th><th>precision all<br>{1}</th>"
      "<th>median translation error<br>top / all (% of d)</th>"
      "<th>median rotation error<br>top / all (deg)</th><th>time per<br>hypothesis</th>"
      "<th>score threshold keeping<br>{2:g} % of right poses {0}</th>"
      "<th>wrong among the<br>poses it accepts</th></tr>\n",
      op(o.loose), op(o.strict), 100 * o.score_keep);
  for (const auto& e : evaluations) {
    s += summary_row(html_escaped(e.dataset.label), e.summary);
    // With several obj_ids, each object's own figures under the dataset's (as in the table
    // eval prints and report.json's "objects").
    for (const ObjectSummary& o : e.objects)
      s += summary_row(fmt::format("&nbsp;&nbsp;obj_id {}", o.obj_id), o.summary);
  }
  return s + "</table>\n";
}

// Both operating points: the threshold, what it keeps, what it lets through, and whether that
// meets the requirement (at most kScoreMaxWrong wrong).
std::string calibration_table(const std::vector<DatasetEvaluation>& evaluations,
                              const EvalOptions& o) {
  std::string s = "<table>\n<tr><th>dataset</th><th>right at</th><th>score threshold</th>"
                  "<th>right poses kept</th><th>wrong among accepted</th>"
                  + fmt::format("<th>at most {:g} % wrong</th></tr>\n", 100 * kScoreMaxWrong);
  for (const auto& e : evaluations)
    for (const auto* c : {&e.summary.score_loose, &e.summary.score_strict}) {
      const OperatingPoint& at = c == &e.summary.score_loose ? o.loose : o.strict;
      s += fmt::format(
          "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
          html_escaped(e.dataset.label), op(at), threshold_cell(*c),
          c->any_right ? fmt::format("{} ({} of {})", pct(c->kept), c->accepted_right, c->right)
                       : std::string("none of ") + std::to_string(c->hypotheses),
          wrong_cell(*c),
          c->any_right ? (c->wrong_fraction <= kScoreMaxWrong ? "yes" : "<b>no</b>") : "&ndash;");
    }
  return s + "</table>\n";
}

// caption is HTML (it may hold colour swatches); alt is plain text.
std::string figure(const std::string& src, const std::string& alt, const std::string& caption) {
  return fmt::format("<figure><a href=\"{0}\"><img src=\"{0}\" alt=\"{1}\"></a><figcaption>{2}"
                     "</figcaption></figure>\n",
                     html_escaped(src), html_escaped(alt), caption);
}

std::string hypotheses_table(const DatasetEvaluation& e, const ImageKey& key, const OperatingPoint& at) {
  std::string s = "<table>\n<tr><th>rank</th><th>score</th><th>top</th>"
                  "<th>matched part</th><th>translation error</th><th>rotation error</th>"
                  "<th>correct</th></tr>\n";
  for (const auto& r : e.summary.results) {
    if (r.scene_id != key.scene_id || r.im_id != key.im_id) continue;
    s += fmt::format("<tr><td>{} {}</td><td>{:g}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                     swatch(rank_colour(r.rank)), r.rank + 1, r.score, r.top ? "&#9733;" : "",
                     r.gt_index >= 0 ? std::to_string(r.gt_index) : "none",
                     num(r.translation_pct, " %"), num(r.rotation_deg, "&deg;"),
                     correct_at(r, at) ? "yes" : "no");
  }
  return s + "</table>\n";
}

std::string pictures_section(const std::vector<DatasetEvaluation>& evaluations,
                             const EvalOptions& o, const std::vector<PicturedImage>& pictures) {
  std::string s;
  for (const auto& p : pictures) {
    const auto& e = evaluations[p.dataset];
    s += fmt::format("<h3>{}: scene {} image {}</h3>\n", html_escaped(e.dataset.label),
                     p.key.scene_id, p.key.im_id);
    s += figure(p.depth, "depth in false colour", fmt::format("Depth in false colour (viridis: near dark, far bright, "
                                     "{:.0f} to {:.0f} mm; black = no data).",
                                     p.depth_range.near_mm, p.depth_range.far_mm));
    s += figure(p.intensity, "intensity image", "Intensity image.");
    s += figure(p.hypotheses, "hypothesis neighbourhoods", "Hypotheses: scene points within one diameter of each detected "
                              "position, coloured by rank (1 = first row); crosses at the "
                              "positions.");
    s += figure(p.detections, "detections over the intensity image",
                fmt::format("Detections: model points at each detected pose, {} correct at "
                            "({:g} %, {:g}&deg;), {} wrong; {} ring: the top-ranked one "
                            "(highest score).",
                            swatch(kCorrect), o.loose.translation_pct, o.loose.rotation_deg,
                            swatch(kWrong), swatch(kTopRing)));
    if (!p.closeup.empty())
      s += figure(p.closeup, "top-ranked detection in the scene cloud", fmt::format("Top-ranked detection: model points {} in the scene "
                                         "cloud {}, seen from the camera (left) and from 60&deg; "
                                         "aside (right).",
                                         swatch(kModelPoints), swatch(kScenePoints)));
    if (!p.picks.empty()) {
      std::string verdicts;
      for (const PickOutcome* pick : p.judged)
        verdicts += fmt::format(" Detection {}: {}.", pick->pick.rank + 1, html_escaped(pick->verdict()));
      s += figure(p.picks, "first picks", fmt::format("First pick: the gripper's outline at the planned "
                  "grasp, the cup's footprint filled, the arrow down the approach; {} succeeds at the "
                  "true poses, {} fails; the picked detection's model points {}.{}",
                  swatch(kCorrect), swatch(kWrong), swatch(kModelPoints), verdicts));
    }
    s += hypotheses_table(e, p.key, o.loose);
  }
  return s;
}

std::string score_section(const std::vector<DatasetEvaluation>& evaluations, const EvalOptions& o,
                          const ReportFiles& files) {
  std::string s = "<h2>Precision against score threshold</h2>\n";
  s += fmt::format(
      "<p>Can the score be trusted? A pose is accepted when its score is at least the threshold. "
      "Over every hypothesis (an unmatched one is wrong), right and wrong at {0}: "
      "<i>precision</i> = right accepted / accepted (1 where nothing is accepted), "
      "<i>kept</i> = right accepted / all right. The calibrated threshold is the highest score "
      "that keeps {1:g} % of the right poses (exact, not on a grid); the score is calibrated when "
      "at most {2:g} % of the poses it accepts are wrong.</p>\n",
      op(o.loose), 100 * o.score_keep, 100 * kScoreMaxWrong);
  if (!files.score_plot.empty())
    s += figure(files.score_plot.filename().string(), "precision against score threshold",
                fmt::format("(a) Precision of the accepted poses and (b) fraction of the right "
                            "poses kept, against the score threshold, right at {}; one curve per "
                            "dataset, coloured as above (a precision curve ends where no pose "
                            "scores that high); dots: each dataset's calibrated threshold; "
                            "dashed: {:g} % precision (a) and {:g} % kept (b).",
                            op(o.loose), 100 * (1 - kScoreMaxWrong), 100 * o.score_keep));
  return s + calibration_table(evaluations, o);
}

}  // namespace

std::string html_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string report_html(const std::vector<DatasetEvaluation>& evaluations,
                        const EvalOptions& o, const ReportFiles& files,
                        const std::vector<PicturedImage>& pictures) {
  std::string s = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                  "<title>binpick evaluation</title>\n";
  s += kStyle;
  s += "</head>\n<body>\n<h1>binpick evaluation</h1>\n";
  s += "<p>Each hypothesis is matched to the ground-truth part nearest in translation. "
       "Translation error: distance between the translations, in % of the part diameter d; "
       "rotation error: angle of R<sub>gt</sub><sup>T</sup> R<sub>est</sub> (the smallest over "
       "the part's symmetries). A hypothesis is correct when both errors are within the "
       "thresholds. <i>top</i>: the top-ranked hypothesis of each image (the highest score); "
       "<i>all</i>: every hypothesis. Time per hypothesis: each image's time divided by its "
       "hypotheses. Score: the detector's verified score in [0, 1] (the fraction of the model "
       "surface visible at the pose that agrees with the measured depth); its calibration is "
       "below.</p>\n";
  s += summary_table(evaluations, o);
  s += "<p>Inputs: ";
  for (std::size_t i = 0; i < evaluations.size(); ++i)
    s += fmt::format("{}<code>{}</code> with <code>{}</code>", i ? "; " : "",
                     html_escaped(evaluations[i].dataset.root.string()),
                     html_escaped(evaluations[i].results.string()));
  s += ".</p>\n";
  for (const auto& w : files.warnings) s += "<p class=\"warn\">" + html_escaped(w) + "</p>\n";
  s += "<h2>Precision against error thresholds</h2>\n";
  if (!files.plot.empty())
    s += figure(files.plot.filename().string(), "precision curves",
                "Precision as a function of the translation threshold (a, b) and of the rotation "
                "threshold (c, d), over all hypotheses (a, c) and over the top-ranked one per "
                "image (b, d); one curve per dataset (the paper's Figure 7).");
  s += score_section(evaluations, o, files);
  s += bop_html_section(evaluations);
  s += fmt::format("<p>Data: <a href=\"{0}\">{0}</a> (the curves), <a href=\"{1}\">{1}</a> "
                   "(the score curves), <a href=\"{2}\">{2}</a> (every hypothesis), "
                   "<a href=\"{3}\">{3}</a> (the numbers above).</p>\n",
                   files.curves_csv.filename().string(),
                   files.score_curves_csv.filename().string(),
                   files.hypotheses_csv.filename().string(), files.json.filename().string());
  if (!pictures.empty()) s += "<h2>Scenes</h2>\n" + pictures_section(evaluations, o, pictures);
  return s + "</body>\n</html>\n";
}

void write_report_html(const std::filesystem::path& path,
                       const std::vector<DatasetEvaluation>& evaluations, const EvalOptions& o,
                       const ReportFiles& files, const std::vector<PicturedImage>& pictures) {
  const std::string text = report_html(evaluations, o, files, pictures);
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace binpick::eval
