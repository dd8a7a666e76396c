// Per-bin cost of the physics half of `binpick synth`: HACD cold and from the cache, and the
// Bullet drop of a full 350-part bin (the paper's scene) for a bracket and a torus.
// With BINPICK_BENCH_SMOKE set, the bin has 20 parts so that ctest's smoke run takes seconds.
//   bench_synth_physics --benchmark_repetitions=3   (medians over seeds 1, 2, 3)
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "synth/decompose/decompose.hpp"
#include "synth/physics/drop.hpp"

namespace binpick {
namespace {

bool smoke_run() { return std::getenv("BINPICK_BENCH_SMOKE") != nullptr; }

// An L-profile (legs 40 and 30 mm, 5 mm thick) extruded 20 mm: diameter about 54 mm, like the
// paper's part (5.2 cm).
Mesh l_bracket() {
  const std::vector<Eigen::Vector2f> outline = {{0, 0}, {40, 0}, {40, 5}, {5, 5}, {5, 30}, {0, 30}};
  const auto n = static_cast<std::uint32_t>(outline.size());
  Mesh m;
  for (float z : {0.0f, 20.0f})
    for (const auto& p : outline) m.positions.emplace_back(p.x(), p.y(), z);
  for (std::uint32_t i : {4u, 5u, 0u, 1u}) {  // fan from the reflex corner
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({3, j, i});
    m.triangles.push_back({n + 3, n + i, n + j});
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({i, j, n + j});
    m.triangles.push_back({i, n + j, n + i});
  }
  return m;
}

// Ring radius 20 mm, tube radius 6 mm: diameter 52 mm.
Mesh torus() {
  const int nu = 32, nv = 12;
  const double ring = 20, tube = 6;
  Mesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      m.positions.emplace_back(float((ring + tube * std::cos(v)) * std::cos(u)),
                               float((ring + tube * std::cos(v)) * std::sin(u)),
                               float(tube * std::sin(v)));
    }
  const auto at = [&](int i, int j) { return std::uint32_t((i % nu) * nv + j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

Mesh part_for(int index) { return index == 0 ? l_bracket() : torus(); }
const char* name_of(int index) { return index == 0 ? "bracket" : "torus"; }

std::filesystem::path bench_cache_dir() {
  return std::filesystem::temp_directory_path() / "binpick-bench-cache";
}

void BM_DecomposeCold(benchmark::State& state) {
  const Mesh part = part_for(static_cast<int>(state.range(0)));
  DecomposeOptions options;
  options.use_cache = false;
  std::size_t hulls = 0;
  for (auto _ : state) hulls = decompose_convex(part, options).hulls.size();
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
  state.counters["hulls"] = static_cast<double>(hulls);
}

void BM_DecomposeCached(benchmark::State& state) {
  const Mesh part = part_for(static_cast<int>(state.range(0)));
  DecomposeOptions options;
  options.cache_dir = bench_cache_dir();
  decompose_convex(part, options);  // fills the cache
  for (auto _ : state) benchmark::DoNotOptimize(decompose_convex(part, options));
  state.SetLabel(name_of(static_cast<int>(state.range(0))));
}

// range(0): the part; range(1): 1 for DropOptions::final_settle_all_dynamic.
void BM_DropBin(benchmark::State& state) {
  const Mesh part = part_for(static_cast<int>(state.range(0)));
  DecomposeOptions decompose;
  decompose.cache_dir = bench_cache_dir();
  const ConvexParts hulls = decompose_convex(part, decompose);
  DropOptions options;
  if (smoke_run()) options.objects = 20;
  options.final_settle_all_dynamic = state.range(1) != 0;
  // Each repetition drops another bin (seeds 1, 2, 3, ...), so the median is over bins, not
  // over one bin replayed.
  static std::map<std::pair<std::int64_t, std::int64_t>, std::uint64_t> last_seed;
  options.seed = ++last_seed[{state.range(0), state.range(1)}];
  DropStats stats;
  for (auto _ : state) stats = drop_parts(hulls, part, options).stats;
  state.SetLabel(std::string(name_of(static_cast<int>(state.range(0)))) +
                 (options.final_settle_all_dynamic ? ", all-dynamic final settle" : "") +
                 (stats.settled ? "" : ", NOT SETTLED: " + stats.message));
  state.counters["parts"] = options.objects;
  state.counters["hulls"] = static_cast<double>(hulls.hulls.size());
  state.counters["sim_s"] = stats.simulated_seconds;
  state.counters["frozen"] = stats.parts_frozen;
  state.counters["left_bin"] = stats.parts_left_bin;
  state.counters["seed"] = static_cast<double>(options.seed);
}

BENCHMARK(BM_DecomposeCold)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DecomposeCached)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DropBin)
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({0, 1})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace binpick

BENCHMARK_MAIN();
