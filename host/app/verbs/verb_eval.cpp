// `binpick eval`: compares detection results (BOP results CSV) with a dataset's ground truth and
// writes a report directory: report.html, report.json, curves.csv, score_curves.csv,
// hypotheses.csv, the precision and score threshold figures and pictures of the first scenes
// (docs/pipeline.md, "eval: errors and precision (paper III-D)").
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "host/app/options/shard_options.hpp"
#include "host/app/verbs/verbs.hpp"
#include "host/core/error.hpp"
#include "host/core/output_lock.hpp"
#include "host/eval/eval_run.hpp"
#include "host/eval/report/bop_report.hpp"
#include "host/eval/report/report_tables.hpp"

namespace binpick::cli {
namespace {

struct EvalArgs {
  std::vector<std::string> datasets, results;
  std::string out;
  std::int64_t pictures = 3;  // wide, so a negative value reaches our range check
  bool json = false;
  bool no_vsd = false;
  double vsd_delta_mm = eval::kBopVsdDelta;
  eval::DatasetLayout layout;
  std::string shard;  // refused: see kUnsharded
};

// Why eval takes no --shard: its curves and statistics need every result at once.
constexpr const char* kUnsharded =
    "its precision curves and score statistics need all results at once; shard `detect` "
    "(whose merged results are the unsharded ones) and evaluate the merged CSV";

std::vector<eval::EvalInput> inputs_of(const EvalArgs& a) {
  if (a.datasets.empty()) throw InputError("--dataset DIR is required (with its --results CSV)");
  if (a.datasets.size() != a.results.size())
    throw InputError(fmt::format(
        "{} --dataset but {} --results: give them in pairs, each dataset followed by its "
        "results CSV (--dataset A --results A.csv --dataset B --results B.csv)",
        a.datasets.size(), a.results.size()));
  std::vector<eval::EvalInput> inputs;
  for (std::size_t i = 0; i < a.datasets.size(); ++i)
    inputs.push_back({a.datasets[i], a.results[i], a.layout});
  return inputs;
}

void print_summary(const std::vector<eval::DatasetEvaluation>& evaluations,
                   const eval::EvalOptions& o) {
  std::cout << fmt::format("{:<24} {:>7} {:>10} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>10}\n",
                           "dataset", "images", "hypotheses",
                           fmt::format("top{:g}/{:g}", o.loose.translation_pct, o.loose.rotation_deg),
                           fmt::format("all{:g}/{:g}", o.loose.translation_pct, o.loose.rotation_deg),
                           fmt::format("top{:g}/{:g}", o.strict.translation_pct, o.strict.rotation_deg),
                           fmt::format("all{:g}/{:g}", o.strict.translation_pct, o.strict.rotation_deg),
                           "med.te%", "med.re", "ms/hyp");
  const auto row = [](const std::string& label, const eval::EvalSummary& s) {
    std::cout << fmt::format(
        "{:<24} {:>7} {:>10} {:>8.1f}% {:>8.1f}% {:>8.1f}% {:>8.1f}% {:>9.2f} {:>9.2f} {:>10.1f}\n",
        label, s.images, s.hypotheses, 100 * s.loose.top, 100 * s.loose.all,
        100 * s.strict.top, 100 * s.strict.all, s.median_translation_pct_all,
        s.median_rotation_deg_all, s.ms_per_hypothesis);
  };
  for (const auto& e : evaluations) {
    row(e.dataset.label, e.summary);
    // With several objects, each one's rows (its top-ranked per image its own).
    for (const auto& o : e.objects) row(fmt::format("  obj_id {}", o.obj_id), o.summary);
  }
  std::cout << eval::bop_summary_lines(evaluations);
  for (const auto& e : evaluations)
    std::cout << fmt::format("{:<24} {}\n", e.dataset.label,
                             eval::calibration_line(e.summary.score_loose, o.loose));
  for (const auto& e : evaluations) {
    if (!e.picks) continue;
    std::size_t wrong = 0, off = 0, hit = 0;
    for (const auto& f : e.picks->firsts) {
      wrong += !f.right;
      off += f.right && !f.on_grasp;
      hit += f.right && f.on_grasp && !f.collision.empty();
    }
    std::cout << fmt::format(
        "{:<24} picks: the first pick succeeds in {} of {} images ({:.1f} %); {} without a pick; "
        "failed: {} on a wrong detection, {} off the true grasp, {} colliding at the true poses\n",
        e.dataset.label, e.picks->success, e.picks->images, 100 * e.picks->rate(),
        e.picks->images - e.picks->picked, wrong, off, hit);
  }
  for (const auto& e : evaluations) {
    const auto& s = e.summary;
    if (s.all_on_nothing == 0 && s.all_on_distractor == 0) continue;
    std::cout << fmt::format(
        "{:<24} landing: {:.1f} % of hypotheses on no part (bin, floor), {:.1f} % on another "
        "object; top-ranked: {:.1f} % / {:.1f} %\n",
        e.dataset.label, 100 * s.all_on_nothing, 100 * s.all_on_distractor,
        100 * s.top_on_nothing, 100 * s.top_on_distractor);
  }
}

void run_eval(const EvalArgs& args) {
  refuse_shard(args.shard, "eval", kUnsharded);
  const auto inputs = inputs_of(args);
  if (args.pictures < 0 || args.pictures > 1000)
    throw InputError(fmt::format("--pictures {} must be in [0, 1000]", args.pictures));
  const std::filesystem::path out = args.out;
  if (std::filesystem::exists(out) && !std::filesystem::is_directory(out))
    throw InputError("--out " + out.string() + " exists and is not a directory");

  eval::ReportOptions options;
  options.out = out;
  options.pictures = int(args.pictures);
  options.eval.vsd = !args.no_vsd;
  options.eval.vsd_delta_mm = args.vsd_delta_mm;
  eval::check(options.eval);
  // Everything is read and checked here, before the first file of the report is written.
  const auto evaluations = eval::evaluate_inputs(inputs, options.eval);
  const OutputLock lock = OutputLock::directory(out);
  const eval::ReportFiles files = eval::write_report(evaluations, options);
  for (const auto& w : files.warnings) std::cerr << "binpick: warning: " << w << "\n";
  if (args.json) {
    std::cout << eval::report_json(evaluations, options.eval).dump(2) << "\n";
    return;
  }
  print_summary(evaluations, options.eval);
  std::cout << "wrote " << files.html.string() << "\n";
}

}  // namespace

void add_eval_verb(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  auto* verb = app.add_subcommand(
      "eval",
      "Evaluate detection results against a dataset's ground truth: translation and rotation "
      "errors, precision curves (all hypotheses and top-ranked per image), per obj_id as well "
      "when the results hold several, BOP's average recalls "
      "(VSD rendered with Vulkan, MSSD and MSPD symmetry-aware), precision against "
      "score threshold (is the score calibrated?), pictures; writes report.html, report.json, "
      "curves.csv, score_curves.csv, hypotheses.csv and PNGs into --out");
  verb->add_option("--dataset", args->datasets,
                   "BOP dataset directory (repeat, each followed by its --results, for one curve "
                   "per noise level)");
  verb->add_option("--results", args->results,
                   "BOP results CSV of the preceding --dataset (scene_id,im_id,obj_id,score,R,t,time)");
  verb->add_option("--out", args->out, "report directory (created if missing)")->required();
  verb->add_option("--split", args->layout.split, "dataset split directory")->capture_default_str();
  verb->add_option("--sensor", args->layout.sensor,
                   "BOP sensor suffix: read scene_gt_NAME.json, scene_camera_NAME.json, "
                   "depth_NAME/ (BOP's industrial datasets)");
  verb->add_option("--pictures", args->pictures, "images pictured per dataset, in [0, 1000]")
      ->capture_default_str();
  verb->add_flag("--json", args->json,
                 "print the summary as JSON (the content of report.json) instead of a table");
  verb->add_flag("--no-vsd", args->no_vsd,
                 "skip BOP's VSD (it renders the model at every estimate and target); AR is then "
                 "the mean of AR_MSSD and AR_MSPD");
  verb->add_option("--vsd-delta", args->vsd_delta_mm,
                   "VSD's visibility tolerance, mm (the BOP toolkit's per-dataset vsd_deltas: 15, "
                   "5 for ITODD)")
      ->capture_default_str();
  add_unsharded_option(verb, args->shard, kUnsharded);
  verb->callback([args] { run_eval(*args); });
}

}  // namespace binpick::cli
