// Per-bin cost of the physics half of `binpick synth`: HACD cold and from the cache, and the
// Bullet drop of a full 350-part bin (the paper's scene) for the tests' L-bracket and torus
// and for the built-in bracket (`binpick synth`'s usual part: two plates with holes; HACD's 11
// hulls merged into 2). Each bin is then checked: deepest overlap, and how far parts move when
// the whole pile is simulated for one more second (drift_*; not timed).
// With BINPICK_BENCH_SMOKE set, the bin has 20 parts so that ctest's smoke run takes seconds.
//   bench_synth_physics --benchmark_repetitions=3   (medians over seeds 1, 2, 3)
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "synth/decompose/decompose.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "synth/physics/drop.hpp"
#include "synth/physics/penetration.hpp"
#include "synth/physics/settle_drift.hpp"
#include "tests/support/test_meshes.hpp"
#include "bench/programs/bench_common.hpp"
#include "bench/programs/pile_counters.hpp"

namespace binpick {
using binpick::bench::add_pile_counters;
using binpick::bench::smoke;

namespace {

// Index 0, 1: the tests' L-bracket (2 hulls) and torus (8 hulls); 2: builtin:bracket. All
// about 52 mm across.
Mesh part_for(int index) {
  return index == 0 ? test::l_bracket() : index == 1 ? test::torus() : make_builtin_part("bracket");
}
const char* name_of(int index) {
  return index == 0 ? "bracket" : index == 1 ? "torus" : "builtin:bracket";
}

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
  if (smoke()) options.objects = 20;
  options.final_settle_all_dynamic = state.range(1) != 0;
  // Each repetition drops another bin (seeds 1, 2, 3, ...), so the median is over bins, not
  // over one bin replayed.
  static std::map<std::pair<std::int64_t, std::int64_t>, std::uint64_t> last_seed;
  options.seed = ++last_seed[{state.range(0), state.range(1)}];
  DropResult result;
  for (auto _ : state) result = drop_parts(hulls, part, options);
  const DropStats& stats = result.stats;
  state.SetLabel(std::string(name_of(static_cast<int>(state.range(0)))) +
                 (options.final_settle_all_dynamic ? ", all-dynamic final settle" : "") +
                 (stats.settled ? "" : ", NOT SETTLED: " + stats.message));
  state.counters["parts"] = options.objects;
  state.counters["hulls"] = static_cast<double>(hulls.hulls.size());
  state.counters["frozen"] = stats.parts_frozen;
  state.counters["left_bin"] = stats.parts_left_bin;
  add_pile_counters(state, hulls, part, options, result);
  state.counters["seed"] = static_cast<double>(options.seed);
}

BENCHMARK(BM_DecomposeCold)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DecomposeCached)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DropBin)
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace binpick

BENCHMARK_MAIN();
