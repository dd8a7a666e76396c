// Rendering a synthetic bin (the paper's setting): 350 parts of a 2.3k-triangle torus, 52 mm
// across, at random poses inside a 600 x 400 x 300 bin seen from 1000 mm, 1600 x 900 pixels.
// Reports ms per render and per stage (raster + copies, g-buffer compute, readback, px_all).
// With BINPICK_BENCH_SMOKE set: a 160 x 90 image and 5 parts.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <random>


#include "synth/render/bin_renderer.hpp"
#include "bench/programs/bench_common.hpp"

using namespace binpick;

using binpick::bench::process_cpu_ms;
using binpick::bench::smoke;

namespace {

// A torus around z: tube radius r, centre-line radius R, smooth normals.
Mesh make_torus(float R, float r, int around, int tube) {
  Mesh m;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < tube; ++j) {
      const float a = 2 * float(M_PI) * i / around, b = 2 * float(M_PI) * j / tube;
      const Eigen::Vector3f n(std::cos(b) * std::cos(a), std::cos(b) * std::sin(a), std::sin(b));
      m.positions.push_back(Eigen::Vector3f(R * std::cos(a), R * std::sin(a), 0) + r * n);
      m.normals.push_back(n);
    }
  auto at = [&](int i, int j) { return std::uint32_t((i % around) * tube + (j % tube)); };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < tube; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

// Uniformly random orientations, centres inside the bin (camera frame: floor at z = 1000).
std::vector<Eigen::Isometry3d> random_bin(int parts, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(-270, 270), y(-170, 170), z(730, 975);
  std::normal_distribution<double> g;
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < parts; ++i) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.linear() = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    p.translation() = Eigen::Vector3d(x(rng), y(rng), z(rng));
    poses.push_back(p);
  }
  return poses;
}

void BM_RenderBin(benchmark::State& state) {
  const bool tiny = smoke();
  const int parts = int(state.range(0));
  const bool count_all = state.range(1) != 0, silhouettes = state.range(1) == 2;
  const Mesh torus = make_torus(18, 8, 48, 24);  // 2304 triangles, 52 mm across
  const RenderCamera camera = tiny ? camera_for_bin(600, 400, 300, 1000, 160, 90) : camera_for_bin();
  BinRenderer renderer(torus, camera);
  const auto poses = random_bin(parts, 1);
  const RenderOptions options{.noise_sigma_mm = 1.0, .seed = 3, .count_unoccluded = count_all,
                               .silhouettes = silhouettes};
  RenderTimings sum;
  std::size_t seen = 0;
  const double cpu_start = process_cpu_ms();
  for (auto _ : state) {
    const RenderedBin r = renderer.render(poses, options);
    benchmark::DoNotOptimize(r.depth_mm.data());
    const RenderTimings& t = renderer.last_timings();
    sum.raster_ms += t.raster_ms, sum.compute_ms += t.compute_ms;
    sum.readback_ms += t.readback_ms, sum.coverage_ms += t.coverage_ms;
    sum.silhouettes_ms += t.silhouettes_ms;
    seen = 0;
    for (auto v : r.px_visible) seen += v;
  }
  using C = benchmark::Counter;
  state.counters["process_cpu_ms"] = C(process_cpu_ms() - cpu_start, C::kAvgIterations);
  state.counters["raster_ms"] = C(sum.raster_ms, C::kAvgIterations);
  state.counters["compute_ms"] = C(sum.compute_ms, C::kAvgIterations);
  state.counters["readback_ms"] = C(sum.readback_ms, C::kAvgIterations);
  state.counters["px_all_ms"] = C(sum.coverage_ms, C::kAvgIterations);
  state.counters["silhouettes_ms"] = C(sum.silhouettes_ms, C::kAvgIterations);
  state.counters["surface_px"] = double(seen);
  state.counters["triangles"] = double(torus.triangles.size() * parts);
}

}  // namespace

// Arguments: parts, count px_all (0 no, 1 yes, 2 also each part's silhouette and depth, as
// synth asks for scene_gt_info.json). Medians over 5 repetitions (1 in the smoke run).
BENCHMARK(BM_RenderBin)
    ->ArgsProduct({{smoke() ? 5 : 350}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Repetitions(smoke() ? 1 : 5)
    ->ReportAggregatesOnly(!smoke());

BENCHMARK_MAIN();
