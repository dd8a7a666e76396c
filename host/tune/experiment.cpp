#include "host/tune/experiment.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>
#include <cmath>
#include <ostream>
#include <set>

#include <fmt/format.h>

#include "host/core/atomic_file.hpp"
#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/detect/batch/detect_step.hpp"
#include "synth/pile_cache.hpp"
#include "synth/synthesize.hpp"
#include "host/core/timing.hpp"

namespace binpick {
namespace fs = std::filesystem;
namespace {

fs::path dataset_dir(const ExperimentOptions& o, double noise) { return o.out / noise_dir_name(noise); }
fs::path results_csv(const ExperimentOptions& o, double noise) {
  return experiment_results_csv(o, noise);
}

// The toolkit-ready copy of a level's results, and OUT/bop/NAME -> ../noise_S so that the
// toolkit finds the dataset under the name the results file gives (OUT/bop as its
// datasets_path). An existing entry of that name that is not the link is left alone, said in
// the log.
void export_for_bop_toolkit(const ExperimentOptions& o, double noise, std::ostream& log) {
  const fs::path copy = o.out / "results" / toolkit_results_name(noise);
  // Through a temporary file like every output: a kill or a full disk leaves no half copy.
  const std::string bytes = read_file_bytes(results_csv(o, noise));
  write_file_atomically(copy, [&](std::ostream& s) { s << bytes; });
  const fs::path link = o.out / "bop" / bop_dataset_name(noise);
  const fs::path target = fs::path("..") / noise_dir_name(noise);
  fs::create_directories(link.parent_path());
  std::error_code ec;
  const bool present = fs::exists(fs::symlink_status(link, ec));
  if (!present) {
    fs::create_directory_symlink(target, link, ec);
    if (ec)
      log << fmt::format("bop    {}: not made ({}); point the toolkit at {}\n", link.string(),
                         ec.message(), dataset_dir(o, noise).string());
  } else if (!fs::is_symlink(link) || fs::read_symlink(link, ec) != target) {
    log << fmt::format("bop    {} exists and is not a link to {}: left as it is\n",
                       link.string(), target.string());
  }
}

SynthOptions synth_options(const ExperimentOptions& o, double noise) {
  SynthOptions s = o.scene;
  s.out = dataset_dir(o, noise);
  s.bins = o.bins;
  s.seed = o.seed;
  s.noise = noise;
  s.width = o.width;
  s.height = o.height;
  s.drop.objects = o.objects;
  s.drop.max_wall_seconds = o.max_wall_seconds;
  s.shard = o.shard;
  return s;
}

}  // namespace

fs::path experiment_results_csv(const ExperimentOptions& o, double noise) {
  return o.out / "results" / (noise_dir_name(noise) + ".csv");
}

std::vector<double> parse_number_list(const std::string& text, const std::string& option,
                                      const std::string& example) {
  if (text.empty()) throw InputError(option + " is empty: give at least one value, e.g. " + example);
  std::vector<double> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size())
      throw InputError(option + " '" + text + "': '" + item + "' is not a number; e.g. " + option +
                       " " + example);
    values.push_back(value);
    start = comma + 1;
  }
  return values;
}

std::vector<double> parse_noise_list(const std::string& text) {
  return parse_number_list(text, "--noise", "0,0.01,0.02");
}

std::string noise_dir_name(double noise) {
  int decimals = 2;
  while (decimals < 9 && std::abs(std::round(noise * std::pow(10.0, decimals)) -
                                  noise * std::pow(10.0, decimals)) > 1e-6)
    ++decimals;
  return fmt::format("noise_{:.{}f}", noise, decimals);
}

std::string bop_dataset_name(double noise) {
  std::string digits = noise_dir_name(noise).substr(std::string("noise_").size());
  std::erase(digits, '.');
  return "noise" + digits;
}

std::string toolkit_results_name(double noise) {
  return "binpick_" + bop_dataset_name(noise) + "-test.csv";
}

void check(const ExperimentOptions& o) {
  if (o.noise.empty()) throw InputError("--noise: give at least one noise level, e.g. 0,0.01,0.02");
  std::set<std::string> names;
  for (double n : o.noise) {
    if (!(std::isfinite(n) && n >= 0 && n <= 1))
      throw InputError(fmt::format("--noise {} must be a fraction of the diameter in [0, 1]", n));
    if (!names.insert(noise_dir_name(n)).second)
      throw InputError(fmt::format("--noise lists {} twice", n));
  }
  if (o.out.empty()) throw InputError("--out: a working directory is required");
  if (fs::exists(o.out) && !fs::is_directory(o.out))
    throw InputError("--out " + o.out.string() + " exists and is not a directory");
  if (o.pictures < 0 || o.pictures > 1000)
    throw InputError(fmt::format("--pictures {} must be in [0, 1000]", o.pictures));
  for (double n : o.noise) validate_synth_options(synth_options(o, n));
  check_train_params(o.train);
  binpick::check(o.detect);
}

ExperimentResult run_experiment(const Model& part, const ExperimentOptions& o, std::ostream& log,
                                const std::vector<Model>& distractors) {
  check(o);
  ExperimentResult r;
  const std::string description = describe(o.part);

  auto start = std::chrono::steady_clock::now();
  PileCache piles;  // each bin's pile is simulated once for all noise levels
  for (double noise : o.noise) {
    const SynthOptions s = synth_options(o, noise);
    const SynthSummary made = synthesize(part, description, s, distractors, &piles);
    r.bins_made += made.bins_made;
    r.bins_reused += made.bins_skipped;
    log << fmt::format("synth  {}: {} bins made, {} already there\n", s.out.string(),
                       made.bins_made, made.bins_skipped) << std::flush;
  }
  r.synth_s = seconds_since(start);

  const TrainedModel model = train_or_reuse(part.mesh, description, o.train, o.out / "model.ppfm");
  r.model = model.path;
  r.model_reused = model.reused;
  r.train_s = model.seconds;
  log << fmt::format("train  {}: {} ({} points, {:.1f} s)\n", model.path.string(),
                     model.reused ? "reused" : "trained", model.model.cloud.points.size(),
                     model.seconds) << std::flush;

  start = std::chrono::steady_clock::now();
  Detector detector(model.model, o.detect);
  std::vector<eval::EvalInput> inputs;
  // Bins 0 .. bins-1 by number: a shard's batch is whole before the other shards' bins exist.
  std::vector<int> bins(std::size_t(o.bins));
  std::iota(bins.begin(), bins.end(), 0);
  for (double noise : o.noise) {
    const BatchSummary b =
        detect_to_csv(detector, model, dataset_dir(o, noise), results_csv(o, noise), o.shard, bins);
    log << fmt::format("detect {}: {}\n", results_csv(o, noise).string(), summary_line(b)) << std::flush;
    r.scenes_missing += b.missing;
    if (b.missing > 0) continue;  // another shard merges this level
    export_for_bop_toolkit(o, noise, log);
    inputs.push_back({dataset_dir(o, noise), results_csv(o, noise), {}});
  }
  r.detect_s = seconds_since(start);
  if (r.scenes_missing > 0) return r;  // the last shard evaluates

  start = std::chrono::steady_clock::now();
  eval::ReportOptions report;
  report.out = o.out / "report";
  report.pictures = o.pictures;
  r.evaluations = eval::evaluate_inputs(inputs, report.eval);
  r.report = eval::write_report(r.evaluations, report);
  r.eval_s = seconds_since(start);
  log << fmt::format("eval   {}\n", r.report.html.string()) << std::flush;
  return r;
}

namespace {

// "-" when the dataset could not be scored the BOP way (no model file).
std::string ar_cell(const eval::BopScores& bop, const eval::MetricRecall& metric) {
  return bop.unavailable.empty() ? fmt::format("{:.3f}", metric.overall.average) : "-";
}
// "-" also when VSD was not computed (no depth image, no Vulkan device, eval --no-vsd).
std::string vsd_cell(const eval::BopScores& bop) {
  return bop.unavailable.empty() && bop.has_vsd && bop.vsd.unavailable.empty()
             ? fmt::format("{:.3f}", bop.vsd.average)
             : "-";
}

}  // namespace

std::string results_table(const std::vector<eval::DatasetEvaluation>& evaluations,
                          const eval::EvalOptions& at) {
  const auto point = [](const char* which, const eval::OperatingPoint& p) {
    return fmt::format("{} {:g}%/{:g}deg", which, p.translation_pct, p.rotation_deg);
  };
  // wrong@90%: of the poses the score threshold keeping 90 % of the right ones accepts, the
  // fraction that is wrong (at the loose point, whose group it sits in).
  const std::string wrong = fmt::format("wrong@{:g}%", 100 * at.score_keep);
  // off part: hypotheses whose pose lies on the bin or floor (no part) or on another object
  // (eval's landing), of the top-ranked ones and of all.
  // BOP AR: BOP's average recalls over its VSD, MSSD and MSPD thresholds (bop_scores.hpp).
  std::string t = fmt::format("{:>7} {:>5} {:>6}  {:^28}  {:^17}  {:^17}  {:>8}  {:^20}\n", "",
                              "", "", point("loose", at.loose), point("strict", at.strict),
                              "off part", "", "BOP AR");
  t += fmt::format(
      "{:>7} {:>5} {:>6}  {:>8} {:>8} {:>10}  {:>8} {:>8}  {:>8} {:>8}  {:>8}  {:>6} {:>6} "
      "{:>6}\n",
      "noise", "bins", "hyps", "top", "all", wrong, "top", "all", "top", "all", "ms/hyp", "VSD",
      "MSSD", "MSPD");
  for (const auto& e : evaluations) {
    const auto& s = e.summary;
    const std::string noise = e.dataset.noise >= 0 ? fmt::format("{:.3g}", e.dataset.noise)
                                                   : e.dataset.label;
    // "-" without a right pose: no threshold keeps any.
    const std::string wrong_cell = s.score_loose.any_right
                                       ? fmt::format("{:.1f}%", 100 * s.score_loose.wrong_fraction)
                                       : std::string("-");
    t += fmt::format("{:>7} {:>5} {:>6}  {:>7.1f}% {:>7.1f}% {:>10}  {:>7.1f}% {:>7.1f}%  "
                     "{:>7.1f}% {:>7.1f}%  {:>8.1f}  {:>6} {:>6} {:>6}\n",
                     noise, s.images, s.hypotheses, 100 * s.loose.top, 100 * s.loose.all,
                     wrong_cell, 100 * s.strict.top, 100 * s.strict.all,
                     100 * (s.top_on_nothing + s.top_on_distractor),
                     100 * (s.all_on_nothing + s.all_on_distractor), s.ms_per_hypothesis,
                     vsd_cell(e.bop), ar_cell(e.bop, e.bop.mssd), ar_cell(e.bop, e.bop.mspd));
  }
  return t;
}

}  // namespace binpick
