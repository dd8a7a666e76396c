// The benchmark's scenes: `binpick synth` bins made one at a time into OUT/dataset, so that each
// bin's physics and rendering seconds are known. They are recorded in OUT/synth_times.json; a
// rerun reuses the bins (synth resumes) and their recorded times. The same piles seen by the
// real-size structured-light camera go to OUT/dataset_real (times in synth_times_real.json).
#pragma once

#include <filesystem>
#include <vector>

#include "bench/lib/bench_options.hpp"
#include "bench/lib/bench_result.hpp"
#include "host/formats/mesh/load_model.hpp"

namespace binpick {
class PileCache;
}

namespace binpick::bench {

std::filesystem::path dataset_dir(const BenchOptions& options);
std::filesystem::path real_dataset_dir(const BenchOptions& options);

// Makes (or reuses) options.bins bins of `part` (the paper's view, or with `real` the real
// sensor's); returns the time of each. `piles` lets the second view reuse the first's physics.
std::vector<SynthBin> make_bench_dataset(const Model& part, const BenchOptions& options,
                                         bool real = false, PileCache* piles = nullptr);

}  // namespace binpick::bench
