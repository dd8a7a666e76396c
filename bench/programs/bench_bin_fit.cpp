// The bin fit (--bin auto, --bin W,D,H; host/detect/bin/) on the analytic scenes of the bin tests
// (tests/detect/bin/bin_scene.hpp, 320 x 240): a bin filling the view that the border gives, the
// same bin small in a cluttered cell found anywhere with and without its size, and a heap with no
// bin (the border and the search anywhere both run, and find nothing: what every image of the
// paper's scene pays). Reports ms per fit and whether a bin was found. Medians over 5
// repetitions; with BINPICK_BENCH_SMOKE set, one.
#include <benchmark/benchmark.h>

#include <string>

#include "bench/programs/bench_common.hpp"
#include "host/detect/bin/bin_fit.hpp"
#include "tests/detect/bin/bin_fit_check.hpp"
#include "tests/detect/bin/bin_scene.hpp"

using namespace binpick;
using binpick::bench::process_cpu_ms;
using binpick::bench::smoke;

namespace {

// 0: a bin filling the view, tilted 20 degrees; 1: a bin a third of the view in a cell (a wall, a
// column, a crate), tilted 25 and turned 25 degrees; 2: a heap on the ground, no bin.
test::BinScene scene_of(int kind) {
  test::BinSceneSpec s;
  if (kind == 0) s.tilt_deg = 20;
  if (kind == 1) {
    s.distance = 2000, s.tilt_deg = 25, s.yaw_deg = 25;
    const double hw = s.W / 2, hd = s.D / 2;
    s.boxes = {{{-1500, hd + 600, -40}, {1500, hd + 640, 1400}},
               {{-hw - 600, -150, -40}, {-hw - 350, 150, 700}},
               {{hw + 300, -200, -40}, {hw + 650, 150, 140}}};
  }
  if (kind == 2) s = test::heap_spec(3);
  return test::make_bin_scene(s);
}

void BM_BinFit(benchmark::State& state) {
  const test::BinScene scene = scene_of(int(state.range(0)));
  const BinSpec spec = state.range(1) ? BinSpec{BinSpec::Mode::sized, {400, 300, 180}}
                                      : BinSpec{BinSpec::Mode::find, Eigen::Vector3d::Zero()};
  (void)test::fit(scene, spec);  // builds the plane kernels outside the timing
  bool found = false, anywhere = false;
  const double cpu_start = process_cpu_ms();
  for (auto _ : state) {
    const BinFit b = test::fit(scene, spec);
    found = b.found, anywhere = b.anywhere;
  }
  state.counters["found"] = found;
  state.counters["anywhere"] = anywhere;
  state.counters["process_cpu_ms"] =
      benchmark::Counter(process_cpu_ms() - cpu_start, benchmark::Counter::kAvgIterations);
}

}  // namespace

// Arguments: the scene (0 a bin filling the view, 1 small in a cell, 2 a heap without a bin);
// the size given (1: --bin 400,300,180; 0: auto).
BENCHMARK(BM_BinFit)
    ->Args({0, 0})->Args({1, 0})->Args({1, 1})->Args({2, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Repetitions(smoke() ? 1 : 5)
    ->ReportAggregatesOnly(!smoke());

BENCHMARK_MAIN();
