// `tune --slurm` without a cluster: --dry-run prints the job array of the first batch (the start
// and its round's values) and makes nothing else; the array's tasks (`tune --points FILE
// --shard K/N`) run by hand measure their shares; `tune --slurm` then finds every point measured,
// submits nothing and writes the table a single process writes (times aside). A task with other
// options, or --shard without --points, is one usage error.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>

#include <fmt/format.h>

#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

const char* kTune =
    "tune --model builtin:bracket --bins 1 --objects 8 --width 480 --height 270 --hypotheses 3 "
    "--rounds 1 --max-evals 3 --budget-ms 100000";

std::string tune(const fs::path& out, const std::string& extra) {
  return fmt::format("{} --out '{}' {}", kTune, out.string(), extra);
}

// tune.csv without the measured columns (ms_per_hypothesis, within_budget, best).
std::string measured_columns(const fs::path& csv) {
  const std::string text = test::slurp(csv);
  std::string out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    for (int i = 0; i < 3; ++i) line = line.substr(0, line.rfind(','));
    out += line + "\n";
    start = end + 1;
  }
  return out;
}

TEST(TuneSlurmCli, TasksByHandThenTheSingleProcessTable) {
  const fs::path dir = test::fresh_temp_dir("tune_slurm_cli");
  auto r = test::run_binpick(tune(dir / "single", ""));
  ASSERT_EQ(r.status, 0) << r.err;

  const fs::path out = dir / "array";
  r = test::run_binpick(tune(out, "--slurm --tasks 2 --dry-run"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("3 points to measure"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("#SBATCH --array=0-1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--shard \"$((SLURM_ARRAY_TASK_ID + 1))/2\""), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("--dry-run"), std::string::npos) << r.out;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("'--points' '([^']+)'"))) << r.out;
  const std::string points = m[1];
  EXPECT_TRUE(fs::is_regular_file(points));
  EXPECT_FALSE(fs::exists(out / "dataset"));  // a dry run makes no dataset
  EXPECT_FALSE(fs::exists(out / "tune.csv"));

  // The tasks need the dataset the --slurm process makes: the single process's is the same.
  fs::copy(dir / "single" / "dataset", out / "dataset", fs::copy_options::recursive);
  for (const char* shard : {"1/2", "2/2"}) {
    r = test::run_binpick(tune(out, fmt::format("--points '{}' --shard {}", points, shard)));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find(" of 3: top "), std::string::npos) << r.out;
  }
  int results = 0;
  for (const auto& e : fs::directory_iterator(out / "evals")) {
    const std::string name = e.path().filename().string();
    results += name.ends_with(".csv") && !name.ends_with(".details.csv");
  }
  EXPECT_EQ(results, 3);
  r = test::run_binpick(tune(out, "--slurm --tasks 2"));  // every point there: no sbatch needed
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("submitting"), std::string::npos) << r.out;
  EXPECT_EQ(measured_columns(out / "tune.csv"), measured_columns(dir / "single" / "tune.csv"));
  EXPECT_TRUE(fs::is_regular_file(out / "best.json"));
  EXPECT_TRUE(fs::is_regular_file(out / "best.ppfm"));

  // A task with other options than the points file's (a parameter the search does not vary);
  // --shard without --points.
  r = test::run_binpick(tune(out, fmt::format("--points '{}' --peaks-per-ref 2", points)));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("other options"), std::string::npos) << r.err;
  r = test::run_binpick(tune(out, "--shard 1/2"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--points"), std::string::npos) << r.err;
  r = test::run_binpick(tune(out, fmt::format("--points '{}' --slurm", points)));
  EXPECT_EQ(r.status, 2);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace binpick
