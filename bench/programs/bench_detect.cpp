// Detection time per hypothesis on the paper's image size (paper section IV: 726 ms at 20 %
// reference points, 70 ms at 2 %): a 1600 x 900 bin of the built-in bracket made by the synth
// pipeline (70 parts, so the physics stays seconds), and one of the built-in plate (a thin part:
// its coplanar pairs share keys, and it runs the in-plane search, so refinement dominates), the
// model trained once, then the whole Detector on the depth image. Counters are ms per hypothesis by stage: preparation (scene
// preparation, highest points, crop, subsampling), voting (features, votes, peaks) and
// clustering (poses, compatibility kernel, grouping). Argument: reference points in per mille.
// With BINPICK_BENCH_SMOKE set: a 160 x 90 bin of 10 parts, one repetition.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include <unistd.h>

#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/detect/batch/detect_batch.hpp"
#include "host/detect/detector.hpp"
#include "host/app/options/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/train/ppf_model.hpp"
#include "synth/synthesize.hpp"
#include "bench/programs/bench_common.hpp"

using namespace binpick;
namespace fs = std::filesystem;

using binpick::bench::process_cpu_ms;
using binpick::bench::smoke;

namespace {

struct Bench {
  Model part;
  PpfModel model;
  DepthImage depth;
  bp_camera cam{};
};

Bench make_bench(const std::string& part) {
  Bench b;
  b.part = cli::load_part({part, {}});
  b.model = train_ppf_model(b.part.mesh, {});
  const fs::path dir = fs::temp_directory_path() /
                       ("binpick_bench_detect_" + std::to_string(::getpid()));
  SynthOptions opt;
  opt.out = dir;
  opt.bins = 1;
  opt.write_cloud = false;
  opt.drop.objects = smoke() ? 10 : 70;
  if (smoke()) opt.width = 160, opt.height = 90;
  synthesize(b.part, part, opt);
  const fs::path scene = dir / "test" / "000000";
  const auto png = read_png16(scene / "depth" / "000000.png");
  const auto cam = bop::read_scene_cameras(scene / "scene_camera.json").at(0);
  b.depth = {png.width, png.height, png.pixels};
  b.cam = image_camera(cam.K, cam.depth_scale, png.width, png.height);
  std::error_code ec;
  fs::remove_all(dir, ec);
  return b;
}

const Bench& bench(const std::string& part) {
  static std::map<std::string, Bench> made;
  auto it = made.find(part);
  if (it == made.end()) it = made.emplace(part, make_bench(part)).first;
  return it->second;
}

void detect_per_hypothesis(benchmark::State& state, const std::string& part) {
  const Bench& b = bench(part);
  DetectParams params;
  params.ref_ratio = double(state.range(0)) / 1000.0;
  Detector detector(b.model, params);
  (void)detector.detect(b.depth, b.cam);  // builds the programs outside the timing
  DetectTimes total;
  std::uint64_t best = 0;
  const double cpu_start = process_cpu_ms();
  for (auto _ : state) {
    DetectTimes t;
    const auto found = detector.detect(b.depth, b.cam, &t);
    best = found.empty() ? 0 : found.front().votes;
    total += t;
  }
  using C = benchmark::Counter;
  const double h = double(std::max<std::size_t>(total.hypotheses, 1));
  state.counters["prepare_ms_per_hyp"] = total.prepare_ms / h;
  state.counters["vote_ms_per_hyp"] = total.vote_ms / h;
  state.counters["cluster_ms_per_hyp"] = total.cluster_ms / h;
  state.counters["refine_ms_per_hyp"] = total.refine_ms / h;
  state.counters["total_ms_per_hyp"] = total.total_ms() / h;
  state.counters["process_cpu_ms"] = C(process_cpu_ms() - cpu_start, C::kAvgIterations);
  state.counters["best_votes"] = double(best);
  state.counters["pixels"] = double(b.depth.raw.size());
}

void BM_DetectPerHypothesis(benchmark::State& state) {
  detect_per_hypothesis(state, "builtin:bracket");
}

void BM_DetectPerHypothesisPlate(benchmark::State& state) {
  detect_per_hypothesis(state, "builtin:plate");
}

}  // namespace

// Argument: reference points per mille of the subsampled scene points (200 = the paper's 20 %).
BENCHMARK(BM_DetectPerHypothesis)
    ->Arg(200)->Arg(20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(smoke() ? 1 : 3);
BENCHMARK(BM_DetectPerHypothesisPlate)
    ->Arg(200)->Arg(20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(smoke() ? 1 : 3);

BENCHMARK_MAIN();
