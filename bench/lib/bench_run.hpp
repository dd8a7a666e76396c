// `binpick bench`: every measurement of the benchmark in one run, in the order a reader needs them:
// the machine's peaks, the paper's scenes (synth, timed per bin), the model (training timed),
// detection per stage at each reference ratio, the scaling sweeps, OpenCV side by side; then
// the report. Progress lines go to `log`; the scenes are reused by a rerun.
#pragma once

#include <iosfwd>

#include "bench/lib/bench_options.hpp"
#include "bench/lib/bench_report.hpp"
#include "bench/lib/bench_result.hpp"

namespace binpick::bench {

struct BenchRun {
  BenchResult result;
  BenchFiles files;
};

// `part` is the model options.part names, loaded.
BenchRun run_bench(const Model& part, const BenchOptions& options, std::ostream& log);

}  // namespace binpick::bench
