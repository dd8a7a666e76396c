// `binpick demo`: the whole loop on a built-in part with no argument, small enough to finish in
// about two minutes on two cores: synthesise a few bins, train the model, detect, evaluate, and
// print a short table and where the report and its pictures are. It is `binpick run` with small
// defaults (host/tune/experiment.hpp), so running it again resumes and is fast.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "host/runtime/cl/cl_device.hpp"
#include "host/app/options/model_options.hpp"
#include "host/app/verbs/verbs.hpp"
#include "host/core/error.hpp"
#include "host/core/output_lock.hpp"
#include "host/tune/experiment.hpp"
#include "host/runtime/vk/vk_context.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "host/core/timing.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;

struct DemoArgs {
  fs::path out = "binpick-demo";
  std::string part = "bracket";
  // 5 bins of 70 parts at two noise levels: about a minute on two idle cores (the physics of
  // one 350-part bin alone takes minutes, docs/synthesis.md), two curves in the report.
  int bins = 5;
  int objects = 70;
  std::uint64_t seed = 1;
  std::string noise = "0,0.02";
};

void run_demo(const DemoArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  const auto& names = builtin_part_names();
  if (std::find(names.begin(), names.end(), a.part) == names.end())
    throw InputError("--part " + a.part + " is not a built-in part (see `binpick parts --list`)");
  ExperimentOptions o;
  o.part = {"builtin:" + a.part, {}};
  o.out = a.out;
  o.noise = parse_noise_list(a.noise);
  o.bins = a.bins;
  o.objects = a.objects;
  o.seed = a.seed;
  check(o);  // before touching the devices: bad options fail fast

  std::cout << "devices\n  OpenCL: " << ocl::Device::shared().description()
            << "\n  Vulkan: " << vkrt::Context::shared().description() << "\n"
            << fmt::format("\n{} bins of {} x {} per noise level ({}), the paper's detection "
                           "parameters, into {}\n",
                           a.bins, a.objects, o.part.spec, a.noise,
                           a.out.string())
            << std::flush;
  const Model part = load_part_finding_symmetries(o.part);
  const OutputLock lock = OutputLock::directory(o.out);
  const auto r = run_experiment(part, o, std::cout);
  for (const auto& w : r.report.warnings) std::cerr << "binpick: warning: " << w << "\n";
  std::cout << "\n" << results_table(r.evaluations) << "\n";
  std::cout << fmt::format("report:   {}\n", r.report.html.string());
  if (!r.report.plot.empty()) std::cout << fmt::format("figure:   {}\n", r.report.plot.string());
  std::cout << fmt::format("pictures: {}\n", (r.report.html.parent_path() / "pictures").string());
  std::cout << fmt::format(
      "time:     {:.0f} s (synth {:.1f}, train {:.1f}, detect {:.1f}, eval {:.1f}){}\n",
      seconds_since(start), r.synth_s,
      r.train_s, r.detect_s, r.eval_s,
      r.bins_reused > 0 || r.model_reused ? "; earlier work in " + a.out.string() + " reused" : "");
}

}  // namespace

void add_demo_verb(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  auto* verb = app.add_subcommand(
      "demo",
      "The whole loop on a built-in part: synth a few small bins, train, detect, eval; print a "
      "table and where the report is. Running it again resumes.");
  verb->add_option("--out", args->out, "working directory for the datasets, model and report")
      ->capture_default_str();
  verb->add_option("--part", args->part, "built-in part (see `binpick parts --list`)")
      ->capture_default_str();
  verb->add_option("--bins", args->bins, "bins per noise level")->capture_default_str();
  verb->add_option("--objects", args->objects, "parts per bin")->capture_default_str();
  verb->add_option("--noise", args->noise,
                   "noise levels, comma separated: depth noise sigma as a fraction of the part "
                   "diameter")
      ->capture_default_str();
  verb->add_option("--seed", args->seed, "random seed")->capture_default_str();
  verb->callback([args] { run_demo(*args); });
}

}  // namespace binpick::cli
