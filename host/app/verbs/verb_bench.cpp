// `binpick bench`: how fast, and faster than what. Measures the paper's scene stage by
// stage, the device's peaks, the scaling sweeps and OpenCV's PPF3DDetector on the same crops,
// and writes bench.md and bench.json (bench/lib/bench_run.hpp). `./run.sh bench` runs it.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <tuple>
#include <memory>

#include <fmt/format.h>

#include "bench/lib/bench_run.hpp"
#include "host/app/options/dataset_options.hpp"
#include "host/app/options/model_options.hpp"
#include "host/app/verbs/verbs.hpp"
#include "host/core/error.hpp"
#include "host/core/output_lock.hpp"
#include "host/tune/experiment.hpp"

namespace binpick::cli {
namespace {

// "W x H" as --real-size takes it ("2064x1544"), or "off" (0 x 0); the range is bench::check's.
std::pair<std::uint32_t, std::uint32_t> parse_real_size(const std::string& text) {
  if (text == "off") return {0, 0};
  unsigned w = 0, h = 0;
  char x = 0, rest = 0;
  if (std::sscanf(text.c_str(), "%u%c%u%c", &w, &x, &h, &rest) != 3 || x != 'x')
    throw InputError(fmt::format("--real-size '{}' must be WIDTHxHEIGHT or off", text));
  return {w, h};
}

ModelArgs default_model() {
  ModelArgs m;
  m.model = "builtin:bracket";
  return m;
}

struct BenchArgs {
  ModelArgs model = default_model();
  bench::BenchOptions options;
  DatasetArgs dataset{.bins = bench::BenchOptions{}.bins, .objects = bench::BenchOptions{}.objects};
  std::string ref_ratios = "0.2,0.02";
  std::string real_size;  // empty: the default (BenchOptions), halved by --quick
  bool quick = false;
};

void run_bench_verb(const BenchArgs& a) {
  bench::BenchOptions given = a.options;
  apply_dataset_args(a.dataset, given);
  bench::BenchOptions o = a.quick ? bench::quick_options(given) : given;
  o.part = part_spec_of(a.model);
  o.ref_ratios = parse_number_list(a.ref_ratios, "--ref-ratios", "0.2,0.02");
  if (!a.real_size.empty()) std::tie(o.real_width, o.real_height) = parse_real_size(a.real_size);
  bench::check(o);  // before the slow stages
  const OutputLock lock = OutputLock::directory(o.out);
  const auto run = bench::run_bench(load_part_finding_symmetries(o.part), o, std::cout);
  std::cout << "\n" << bench::bench_markdown(run.result) << "\n"
            << fmt::format("report: {}\n        {}\n", run.files.markdown.string(),
                           run.files.json.string());
  if (!run.files.plot.empty()) std::cout << fmt::format("        {}\n", run.files.plot.string());
}

}  // namespace

void add_bench_verb(CLI::App& app) {
  auto a = std::make_shared<BenchArgs>();
  auto* verb = app.add_subcommand(
      "bench",
      "Benchmark on the paper's scene (1600 x 900, 350 parts): detection per stage at 20 % and "
      "2 % reference points, the same bins at the real sensor's size (2064 x 1544, structured "
      "light), throughput against the device's measured peaks, scaling, synth "
      "and training times, and OpenCV's PPF3DDetector side by side when its runner was built. "
      "Writes bench.md and bench.json; a rerun reuses the scenes.");
  add_model_options(verb, a->model, false);
  auto& o = a->options;
  verb->add_option("--out", o.out, "directory for the report, the scenes and the crops")
      ->capture_default_str();
  add_dataset_options(verb, a->dataset, "scenes measured", false);
  verb->add_option("--repeats", o.repeats, "timed runs per measurement (medians reported)")
      ->capture_default_str();
  verb->add_option("--ref-ratios", a->ref_ratios,
                   "reference point ratios measured, comma separated (the paper's 20 % and 2 %)")
      ->capture_default_str();
  verb->add_option("--opencv", o.opencv,
                   "OpenCV's runner: auto (opencv_ppf3d next to binpick, if built), off, or a "
                   "path")
      ->capture_default_str();
  verb->add_option("--real-size", a->real_size,
                   fmt::format("the same bins also seen by a structured-light camera of this "
                               "size ({:g} m away, tilted {:g} degrees) and detected at the "
                               "defaults; off: not measured",
                               o.real_camera_height_mm / 1000, o.real_camera_tilt_deg))
      ->default_str(fmt::format("{}x{}", o.real_width, o.real_height));
  verb->add_flag("--quick", a->quick,
                 "a small scene, one repetition, short sweeps: seconds, to check the bench runs");
  verb->callback([a] { run_bench_verb(*a); });
}

}  // namespace binpick::cli
