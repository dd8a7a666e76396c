// PPF model build time and table size: the three built-in parts at the paper's parameters, and
// a 5,000-point model (a sampled sphere, to scale the N^2 pair stage). Counters: model points,
// table entries, distinct keys, table MB, and the per-stage times of the last run (ms).
// Under BINPICK_BENCH_SMOKE only the bolt runs (ctest's smoke run).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <numbers>
#include <random>
#include <string>

#include "host/train/ppf_features.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/ppf_table.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "bench/programs/bench_common.hpp"

using namespace binpick;

using binpick::bench::smoke;

namespace {

void report(benchmark::State& state, std::size_t points, const PpfTable& table,
            const PpfTableTimes& t) {
  state.counters["points"] = double(points);
  state.counters["entries"] = double(table.entries.size());
  state.counters["keys"] = double(table.distinct_keys());
  state.counters["table_MB"] =
      double(table.entries.size() * sizeof(bp_ppf_entry) + table.offsets.size() * 4) / 1e6;
  state.counters["count_ms"] = t.count_s * 1e3;
  state.counters["scatter_ms"] = t.scatter_s * 1e3;
}

void BM_TrainBuiltinPart(benchmark::State& state, const std::string& name) {
  const Mesh mesh = make_builtin_part(name);
  train_ppf_model(mesh, PpfTrainParams{});  // warm PoCL's kernel cache for these sizes
  PpfTrainStats st;
  PpfModel model;
  for (auto _ : state) model = train_ppf_model(mesh, PpfTrainParams{}, &st);
  report(state, st.points, model.table, st.table);
  state.counters["sample_ms"] = st.sample_s * 1e3;
  state.counters["subsample_ms"] = st.subsample_s * 1e3;
}

// n points on a sphere of diameter 52 mm with radial normals: the table stage alone.
void BM_TableSphere(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::mt19937 rng(3);
  std::normal_distribution<float> g;
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f v = Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized();
    cloud.points.push_back(26.0f * v);
    cloud.normals.push_back(v);
  }
  const bp_ppf_quant q = make_ppf_quant(52.0f, 20, 30);
  build_ppf_table(ocl::Device::shared(), cloud, q);  // warm-up
  PpfTableTimes t;
  PpfTable table;
  for (auto _ : state) table = build_ppf_table(ocl::Device::shared(), cloud, q, &t);
  report(state, n, table, t);
}

}  // namespace

BENCHMARK_CAPTURE(BM_TrainBuiltinPart, bolt, std::string("bolt"))->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  if (!smoke()) {
    benchmark::RegisterBenchmark("BM_TrainBuiltinPart/bracket", BM_TrainBuiltinPart,
                                 std::string("bracket"))->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("BM_TrainBuiltinPart/tee", BM_TrainBuiltinPart,
                                 std::string("tee"))->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("BM_TableSphere", BM_TableSphere)
        ->Arg(5000)->Unit(benchmark::kMillisecond)->Iterations(3);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
