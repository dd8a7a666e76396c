// The Bullet drop of a full 350-part bin of each built-in part (`binpick synth --model
// builtin:NAME`, default options), one benchmark per part and seed, and how realistic the pile
// is: parts placed and not at rest, the deepest overlap between two parts, and how far parts
// move when the whole pile is released for one more second (drift_*; not timed). The numbers
// of docs/synthesis.md come from here. One part and seed per run keeps runs short on a shared
// machine and lets two run side by side:
//   bench_synth_builtin --benchmark_filter='BM_DropBuiltin/tee/seed:2$'
// With BINPICK_BENCH_SMOKE set, a bin has 20 parts and only the first seed runs. With
// BINPICK_BENCH_NO_SKIP set, every pair of hulls gets Bullet's contact test (no
// separated_pair_skip.hpp): the same bins, for timing what the skip saves.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "synth/decompose/decompose.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "synth/physics/drop.hpp"
#include "synth/physics/penetration.hpp"
#include "synth/physics/settle_drift.hpp"
#include "bench/programs/bench_common.hpp"
#include "bench/programs/pile_counters.hpp"

namespace binpick {
using binpick::bench::add_pile_counters;
using binpick::bench::smoke;

namespace {

constexpr int kSeeds = 3;

void drop_builtin(benchmark::State& state, const std::string& name, std::uint64_t seed) {
  const Mesh part = make_builtin_part(name);
  DecomposeOptions decompose;  // HACD once per part, in bench_synth_physics's cache
  decompose.cache_dir = std::filesystem::temp_directory_path() / "binpick-bench-cache";
  const ConvexParts hulls = decompose_convex(part, decompose);
  DropOptions options;
  if (smoke()) options.objects = 20;
  if (std::getenv("BINPICK_BENCH_NO_SKIP")) options.skip_apart_hulls = false;
  options.seed = seed;
  DropResult result;
  double wall = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    result = drop_parts(hulls, part, options);
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const DropStats& stats = result.stats;
  state.SetLabel(name + (stats.settled ? "" : ", NOT SETTLED: " + stats.message));
  state.counters["wall_s"] = wall;
  state.counters["placed"] = static_cast<double>(result.poses.size());
  state.counters["not_at_rest"] = static_cast<double>(stats.unsettled.size());
  state.counters["thawed"] = stats.parts_thawed;
  add_pile_counters(state, hulls, part, options, result);
}

const bool registered = [] {
  for (const std::string& name : builtin_part_names())
    for (int seed = 1; seed <= (smoke() ? 1 : kSeeds); ++seed)
      benchmark::RegisterBenchmark(("BM_DropBuiltin/" + name + "/seed:" + std::to_string(seed)).c_str(),
                                   [name, seed](benchmark::State& state) {
                                     drop_builtin(state, name, std::uint64_t(seed));
                                   })
          ->Iterations(1)
          ->Unit(benchmark::kSecond);
  return true;
}();

}  // namespace
}  // namespace binpick

BENCHMARK_MAIN();
