// What the PoCL device can do at best (bench/lib/machine_peak.hpp): STREAM triad bandwidth,
// FMA and integer throughput, random lookups from a table out of cache and from one in L2.
// The yardsticks `binpick bench` reports each detection stage against. Each iteration is one whole
// measurement (itself the best of several launches per kernel); the counters are the medians
// over iterations. Under BINPICK_BENCH_SMOKE one quick measurement runs (not peaks).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "bench/lib/machine_peak.hpp"
#include "bench/programs/bench_common.hpp"

using namespace binpick;

using binpick::bench::smoke;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2.0;
}

void BM_MachinePeak(benchmark::State& state) {
  PeakOptions opt;
  opt.quick = smoke();
  auto& dev = ocl::Device::shared();
  std::vector<MachinePeak> runs;
  for (auto _ : state) runs.push_back(measure_machine_peak(dev, opt));
  auto counter = [&](const char* name, double MachinePeak::*field) {
    std::vector<double> v;
    for (const MachinePeak& p : runs) v.push_back(p.*field);
    state.counters[name] = median(v);
  };
  counter("stream_GB_s", &MachinePeak::stream_gb_s);
  counter("fma_GFLOP_s", &MachinePeak::fma_gflop_s);
  counter("int_Gop_s", &MachinePeak::int_gop_s);
  counter("gather_Glookup_s", &MachinePeak::gather_glookup_s);
  counter("gather_L2_Glookup_s", &MachinePeak::gather_cached_glookup_s);
  counter("measure_s", &MachinePeak::seconds);
  state.SetLabel(describe(runs.back()));
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::RegisterBenchmark("BM_MachinePeak", BM_MachinePeak)
      ->Unit(benchmark::kMillisecond)->Iterations(smoke() ? 1 : 5);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
