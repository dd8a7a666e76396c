// Scene preparation of detection on the paper's image size: a 1600 x 900 depth image of a
// synthetic surface (a floor 1000 mm away under 400 random Gaussian bumps, 0.5 mm noise, 2 %
// holes). Reports ms per stage: upload, points, normals (unless turned off), lowpass (and read
// back when asked), then the 5 highest points and the crop of one neighbourhood on the device-resident scene.
// Medians over 5 repetitions. With BINPICK_BENCH_SMOKE set: a 160 x 90 image, one repetition.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <random>


#include "host/detect/hypotheses/hypotheses.hpp"
#include "host/detect/scene/scene_crop.hpp"
#include "host/detect/scene/scene_prepare.hpp"
#include "bench/programs/bench_common.hpp"

using namespace binpick;

using binpick::bench::process_cpu_ms;
using binpick::bench::smoke;

namespace {

struct Scene {
  DepthImage depth;
  bp_camera cam{};
};

// The surface seen by a camera 1000 mm above the floor; the focal length puts a 640 mm wide
// bin in view, as in the paper's setting.
Scene bumpy_scene(std::uint32_t w, std::uint32_t h) {
  const float f = w * 1000.0f / 640.0f;
  Scene s{{w, h, std::vector<std::uint16_t>(std::size_t(w) * h)}, {f, f, (w - 1) / 2.0f, (h - 1) / 2.0f, 0.1f, w, h, 0}};
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  std::normal_distribution<float> noise(0.0f, 0.5f);
  struct Bump { float x, y, height, sigma; };
  std::vector<Bump> bumps;
  for (int i = 0; i < 400; ++i)
    bumps.push_back({(U(rng) - 0.5f) * 640, (U(rng) - 0.5f) * 360, 20 + 200 * U(rng), 10 + 30 * U(rng)});
  for (std::uint32_t v = 0; v < h; ++v)
    for (std::uint32_t u = 0; u < w; ++u) {
      if (U(rng) < 0.02f) continue;  // no data
      // Bumps as a height field over the floor's (x, y): good enough for timing.
      const float x = (u - s.cam.cx) / f * 1000.0f, y = (v - s.cam.cy) / f * 1000.0f;
      float height = 0;
      for (const Bump& b : bumps) {
        const float d2 = (x - b.x) * (x - b.x) + (y - b.y) * (y - b.y);
        if (d2 < 9 * b.sigma * b.sigma) height = std::max(height, b.height * std::exp(-d2 / (2 * b.sigma * b.sigma)));
      }
      s.depth.raw[std::size_t(v) * w + u] = std::uint16_t(std::lround((1000.0f - height + noise(rng)) / 0.1f));
    }
  return s;
}

const Scene& scene() {
  static const Scene s = smoke() ? bumpy_scene(160, 90) : bumpy_scene(1600, 900);
  return s;
}

void BM_PrepareScene(benchmark::State& state) {
  const Scene& s = scene();
  ScenePrepOptions opt;
  opt.read_back = state.range(0) != 0;
  opt.normals_everywhere = state.range(1) != 0;
  (void)prepare_scene(ocl::Device::shared(), s.depth, s.cam, opt);  // builds the programs outside the timing
  std::map<std::string, double> sum;
  const double cpu_start = process_cpu_ms();
  for (auto _ : state) {
    const PreparedScene p = prepare_scene(ocl::Device::shared(), s.depth, s.cam, opt);
    for (const StageTime& t : p.timings) sum[t.stage] += t.ms;
  }
  for (const auto& [stage, ms] : sum)
    state.counters[stage + "_ms"] = benchmark::Counter(ms, benchmark::Counter::kAvgIterations);
  state.counters["process_cpu_ms"] =
      benchmark::Counter(process_cpu_ms() - cpu_start, benchmark::Counter::kAvgIterations);
  state.counters["pixels"] = double(s.depth.raw.size());
}

void BM_Hypotheses(benchmark::State& state) {
  const Scene& s = scene();
  ScenePrepOptions opt;
  opt.read_back = false;
  const PreparedScene p = prepare_scene(ocl::Device::shared(), s.depth, s.cam, opt);
  const HypothesisOptions hyp{std::uint32_t(state.range(0)), 60.0f};
  std::size_t found = 0, cropped = 0;
  double hyp_ms = 0, crop_ms = 0;
  const double cpu_start = process_cpu_ms();
  for (auto _ : state) {
    Stopwatch clock;
    const auto h = find_hypotheses(p, hyp);
    hyp_ms += clock.lap();
    found = h.size();
    if (!h.empty()) cropped = crop_sphere(p, {h[0].point, 60.0f, true}).points.size();
    crop_ms += clock.lap();
  }
  using C = benchmark::Counter;
  state.counters["hypotheses_ms"] = C(hyp_ms, C::kAvgIterations);
  state.counters["crop_ms"] = C(crop_ms, C::kAvgIterations);
  state.counters["process_cpu_ms"] = C(process_cpu_ms() - cpu_start, C::kAvgIterations);
  state.counters["found"] = double(found);
  state.counters["crop_points"] = double(cropped);
}

}  // namespace

// Arguments: read the prepared images back to the host (0/1); normals of every pixel (0/1: the
// detector's preparation has none, it computes them around the hypotheses only).
BENCHMARK(BM_PrepareScene)
    ->Args({0, 1})->Args({1, 1})->Args({0, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Repetitions(smoke() ? 1 : 5)
    ->ReportAggregatesOnly(!smoke());
// Argument: number of hypotheses (the paper's 5).
BENCHMARK(BM_Hypotheses)
    ->Arg(5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Repetitions(smoke() ? 1 : 5)
    ->ReportAggregatesOnly(!smoke());

BENCHMARK_MAIN();
