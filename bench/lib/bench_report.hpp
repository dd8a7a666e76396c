// The benchmark's report: bench.md (tables to read) and bench.json (every number, for scripts
// and for comparing runs), written atomically into the output directory, plus scaling.png when
// gnuplot is there.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "bench/lib/bench_result.hpp"

namespace binpick::bench {

std::string bench_markdown(const BenchResult& result);
nlohmann::json bench_json(const BenchResult& result);

struct BenchFiles {
  std::filesystem::path markdown, json, plot;  // plot empty without gnuplot
};
BenchFiles write_bench_report(const BenchResult& result, const std::filesystem::path& dir);

}  // namespace binpick::bench
