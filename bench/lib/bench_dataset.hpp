// The benchmark's scenes: `binpick synth` bins made one at a time into OUT/dataset, so that each
// bin's physics and rendering seconds are known. They are recorded in OUT/synth_times.json; a
// rerun reuses the bins (synth resumes) and their recorded times.
#pragma once

#include <filesystem>
#include <vector>

#include "bench/lib/bench_options.hpp"
#include "bench/lib/bench_result.hpp"
#include "host/formats/mesh/load_model.hpp"

namespace binpick::bench {

std::filesystem::path dataset_dir(const BenchOptions& options);

// Makes (or reuses) options.bins bins of `part`; returns the time of each.
std::vector<SynthBin> make_bench_dataset(const Model& part, const BenchOptions& options);

}  // namespace binpick::bench
