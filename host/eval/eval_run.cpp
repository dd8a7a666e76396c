#include "host/eval/eval_run.hpp"

#include <algorithm>
#include <iostream>
#include <set>

#include <fmt/format.h>

#include "host/formats/bop/results_csv.hpp"
#include "host/core/error.hpp"
#include "host/eval/report/gnuplot.hpp"
#include "host/eval/report/precision_plot.hpp"
#include "host/eval/report/report_pictures.hpp"
#include "host/eval/report/report_tables.hpp"
#include "host/eval/report/score_plot.hpp"
#include "host/eval/report/report_html.hpp"

namespace binpick::eval {

std::vector<DatasetEvaluation> evaluate_inputs(const std::vector<EvalInput>& inputs,
                                               const EvalOptions& options) {
  if (inputs.empty()) throw InputError("eval needs at least one --dataset with its --results");
  std::vector<DatasetEvaluation> out;
  for (const auto& in : inputs) {
    DatasetEvaluation e;
    e.dataset = load_dataset(in.dataset, in.layout);
    e.results = in.results;
    const auto rows = bop::read_results_csv(in.results);
    try {
      e.summary = evaluate(e.dataset, rows, options);
      e.objects = per_object(e.dataset, e.summary, options);
      e.bop = bop_scores(e.dataset, rows, {options.vsd, options.vsd_delta_mm});
      // detect --picks wrote its picks beside the results: judged at the true poses.
      std::filesystem::path picks = in.results;
      picks.replace_extension(".picks.csv");
      if (std::filesystem::is_regular_file(picks)) {
        std::set<int> obj_ids;
        for (const auto& [key, image] : e.dataset.images)
          for (const auto& gt : image.gt) obj_ids.insert(gt.obj_id);
        e.picks = evaluate_picks(e.dataset, e.summary, read_first_picks(picks),
                                 sample_part_surfaces(e.dataset, obj_ids),
                                 synth_bin_interior(in.dataset), options.loose);
      }
    } catch (const InputError& err) {
      throw InputError(in.results.string() + ": " + err.what());
    }
    e.curves = figure7_curves(e.summary.results);
    e.score_curve = score_curve(e.summary.results, options.loose);
    out.push_back(std::move(e));
  }
  const bool all_known = std::all_of(out.begin(), out.end(),
                                     [](const auto& e) { return e.dataset.noise >= 0; });
  if (all_known)
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
      return a.dataset.noise < b.dataset.noise;
    });
  return out;
}

ReportFiles write_report(const std::vector<DatasetEvaluation>& evaluations,
                         const ReportOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(options.out, ec);
  if (ec || !fs::is_directory(options.out))
    throw InputError("cannot create report directory " + options.out.string() +
                     (ec ? ": " + ec.message() : ""));
  ReportFiles files;
  files.curves_csv = options.out / "curves.csv";
  files.score_curves_csv = options.out / "score_curves.csv";
  files.hypotheses_csv = options.out / "hypotheses.csv";
  files.json = options.out / "report.json";
  files.html = options.out / "report.html";

  std::vector<LabelledCurves> curves;
  for (const auto& e : evaluations) curves.push_back({e.dataset.label, e.curves});
  std::vector<LabelledScoreCurve> score_curves;
  for (const auto& e : evaluations) {
    score_curves.push_back({e.dataset.label, e.score_curve, e.summary.score_loose});
    if (auto w = score_range_warning(e.dataset.label, e.summary.score_loose); !w.empty())
      files.warnings.push_back(std::move(w));
  }
  write_curves_csv(files.curves_csv, curves);
  write_score_curves_csv(files.score_curves_csv, score_curves);
  write_hypotheses_csv(files.hypotheses_csv, evaluations);
  write_report_json(files.json, evaluations, options.eval);

  const bool any_plottable = std::any_of(score_curves.begin(), score_curves.end(),
                                         [](const auto& c) { return plottable(c.curve); });
  if (const auto gnuplot = find_gnuplot()) {
    try {
      plot_figure7(*gnuplot, options.out / "precision.png", curves);
      files.plot = options.out / "precision.png";
    } catch (const std::exception& e) {
      files.warnings.push_back(std::string("no precision plot: ") + e.what());
    }
    // Nothing to draw when no dataset has rows, all with scores in [0, 1] (the warnings above
    // name the datasets whose scores are not).
    if (any_plottable) {
      try {
        plot_score_threshold(*gnuplot, options.out / "score_threshold.png", score_curves,
                             options.eval.loose);
        files.score_plot = options.out / "score_threshold.png";
      } catch (const std::exception& e) {
        files.warnings.push_back(std::string("no score threshold plot: ") + e.what());
      }
    }
  } else {
    files.warnings.push_back(
        "no precision and score threshold plots: gnuplot is not on PATH (Debian: gnuplot-nox)");
  }

  std::vector<PicturedImage> pictured;
  for (std::size_t d = 0; d < evaluations.size(); ++d) {
    auto more = write_pictures(evaluations[d], d, options, files.warnings);
    pictured.insert(pictured.end(), more.begin(), more.end());
  }
  write_report_html(files.html, evaluations, options.eval, files, pictured);
  return files;
}

}  // namespace binpick::eval
