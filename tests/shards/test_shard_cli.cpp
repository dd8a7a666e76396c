// Sharded batches as a user runs them: synth's and detect's shards, run one after the other,
// give byte for byte the unsharded output (detect: the time column aside), the shard that
// finishes last merges, `binpick merge` names what is missing and is idempotent, a shard of
// another batch is refused while one is unfinished, `--slurm --dry-run` prints the job array of
// the shards still to do, `run`'s shards end in the unsharded report, and bad sharding options
// are one usage error.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

class ShardCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::fresh_temp_dir("shard_cli"));
    const auto t = test::run_binpick("train --model builtin:bracket --out " + model());
    ASSERT_EQ(t.status, 0) << t.err;
    const auto s = test::run_binpick(synth("data", "--bins 3"));
    ASSERT_EQ(s.status, 0) << s.err;
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(*dir_, ec);
    delete dir_;
    dir_ = nullptr;
  }
  static std::string model() { return (*dir_ / "bracket.ppfm").string(); }
  static fs::path path(const std::string& name) { return *dir_ / name; }
  // Small bins (8 parts in a 300 x 200 mm bin, 480 x 270 pixels): a second or less each.
  static std::string synth(const std::string& out, const std::string& extra) {
    return fmt::format(
        "synth --model builtin:bracket --out '{}' --objects 8 --width 480 --height 270 "
        "--bin-size 300,200,150 --camera-height 600 --no-cloud --cache-dir '{}' {}",
        path(out).string(), path("cache").string(), extra);
  }
  static std::string detect(const std::string& out, const std::string& extra) {
    return fmt::format("detect --model '{}' --dataset '{}' --out '{}' --hypotheses 3 {}", model(),
                       path("data").string(), path(out).string(), extra);
  }
  static fs::path* dir_;
};
fs::path* ShardCli::dir_ = nullptr;

TEST_F(ShardCli, SynthShardsMakeTheUnshardedDataset) {
  auto r = test::run_binpick(synth("sharded", "--bins 3 --shard 1/2"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("shard 1/2 done; 1 bins of other shards still to make"), std::string::npos)
      << r.out;
  EXPECT_TRUE(fs::exists(path("sharded") / "test" / "000002" / "scene_gt.json"));
  EXPECT_FALSE(fs::exists(path("sharded") / "test" / "000001"));
  r = test::run_binpick("merge " + path("sharded").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("bins 1 are missing (shards 2/2)"), std::string::npos) << r.err;
  r = test::run_binpick(synth("sharded", "--bins 3 --slurm --tasks 2 --dry-run"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("#SBATCH --array=1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("#SBATCH --job-name=binpick-synth\n"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(path("sharded") / "shards" / "slurm"));  // a dry run writes nothing

  r = test::run_binpick(synth("sharded", "--bins 3 --shard 2/2"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("all 3 bins present"), std::string::npos) << r.out;
  for (int b = 0; b < 3; ++b) {
    const fs::path one = path("data") / "test" / fmt::format("{:06d}", b);
    const fs::path two = path("sharded") / "test" / fmt::format("{:06d}", b);
    for (const char* file : {"scene_gt.json", "scene_gt_info.json", "scene_camera.json",
                             "depth/000000.png"})
      EXPECT_EQ(test::slurp(one / file), test::slurp(two / file)) << b << " " << file;
    EXPECT_FALSE(test::slurp(one / "depth/000000.png").empty());
  }
  r = test::run_binpick("merge " + path("sharded").string());
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST_F(ShardCli, DetectShardsMergeIntoTheUnshardedResults) {
  auto r = test::run_binpick(detect("whole.csv", ""));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string whole = test::slurp(path("whole.csv"));
  ASSERT_GT(std::count(whole.begin(), whole.end(), '\n'), 3);

  r = test::run_binpick(detect("parts.csv", "--shard 3/3"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("shard 3/3 done; 2 scenes of other shards still to do"), std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(path("parts.csv")));
  r = test::run_binpick("merge " + path("parts.csv").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("scenes 0-1 are not done yet"), std::string::npos) << r.err;
  // A shard of another split of the same output is refused while this batch is unfinished.
  r = test::run_binpick(detect("parts.csv", "--shard 1/2"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unfinished sharded batch"), std::string::npos) << r.err;
  // --slurm --dry-run: only the shards still to do are in the array.
  r = test::run_binpick(detect("parts.csv", "--slurm --tasks 3 --dry-run --partition p"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("#SBATCH --array=0-1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("#SBATCH --partition=p\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--shard \"$((SLURM_ARRAY_TASK_ID + 1))/3\""), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("--dry-run"), std::string::npos) << r.out;

  for (const char* shard : {"1/3", "2/3"}) {
    r = test::run_binpick(detect("parts.csv", fmt::format("--shard {}", shard)));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  EXPECT_NE(r.out.find("wrote"), std::string::npos) << r.out;  // the last shard merged
  const std::string merged = test::slurp(path("parts.csv"));
  EXPECT_EQ(test::without_time(merged), test::without_time(whole));
  EXPECT_EQ(test::slurp(path("parts.details.csv")), test::slurp(path("whole.details.csv")));
  r = test::run_binpick("merge " + path("parts.csv").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(test::slurp(path("parts.csv")), merged);  // idempotent
  r = test::run_binpick("merge " + path("parts.csv.parts").string());
  EXPECT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(detect("parts.csv", "--slurm --tasks 3 --dry-run"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("#SBATCH --array=0-2\n"), std::string::npos) << r.out;  // dry run: all
}

// report.json without what depends on the run's directory and its timing.
nlohmann::json comparable_report(const fs::path& file) {
  nlohmann::json j = nlohmann::json::parse(test::slurp(file));
  for (auto& d : j.at("datasets"))
    for (const char* key : {"dataset", "results", "ms_per_hypothesis"}) d.erase(key);
  return j;
}

TEST_F(ShardCli, RunShardsWriteTheUnshardedReport) {
  const std::string run = fmt::format(
      "run --model builtin:bracket --bins 3 --objects 8 --width 480 --height 270 --hypotheses 3 "
      "--noise 0,0.02 --pictures 1 --out '{}'",
      path("run").string());
  const std::string sharded = fmt::format(
      "run --model builtin:bracket --bins 3 --objects 8 --width 480 --height 270 --hypotheses 3 "
      "--noise 0,0.02 --pictures 1 --out '{}'",
      path("run_sharded").string());
  auto r = test::run_binpick(run);
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(sharded + " --shard 2/2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("shard 2/2 done; 4 scenes of other shards still to detect"),
            std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(path("run_sharded") / "report"));
  r = test::run_binpick("merge " + path("run_sharded").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("run the same command without --shard"), std::string::npos) << r.err;
  r = test::run_binpick(sharded + " --shard 1/2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("report: "), std::string::npos) << r.out;  // the last shard reports
  for (const char* level : {"noise_0.00", "noise_0.02"}) {
    const fs::path csv = fs::path("results") / (std::string(level) + ".csv");
    EXPECT_EQ(test::without_time(test::slurp(path("run_sharded") / csv)),
              test::without_time(test::slurp(path("run") / csv))) << level;
    EXPECT_EQ(test::slurp(path("run_sharded") / level / "test" / "000001" / "depth" / "000000.png"),
              test::slurp(path("run") / level / "test" / "000001" / "depth" / "000000.png"));
  }
  EXPECT_EQ(comparable_report(path("run_sharded") / "report" / "report.json"),
            comparable_report(path("run") / "report" / "report.json"));
  EXPECT_EQ(test::slurp(path("run_sharded") / "report" / "curves.csv"),
            test::slurp(path("run") / "report" / "curves.csv"));
}

TEST_F(ShardCli, BadShardingIsOneUsageError) {
  for (const std::string& args :
       {detect("bad.csv", "--shard 0/2"), detect("bad.csv", "--shard 3/2"),
        detect("bad.csv", "--tasks 3"), detect("bad.csv", "--dry-run"),
        detect("bad.csv", "--slurm --shard 1/2"), detect("bad.csv", "--slurm --tasks 0"),
        synth("bad", "--bins 2 --shard 1/x"),
        std::string("eval --dataset x --results y.csv --out z --shard 1/2"),
        std::string("merge ") + path("nothing").string()}) {
    const auto r = test::run_binpick(args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(path("bad.csv"))) << args;
  }
  const auto r = test::run_binpick("eval --dataset x --results y.csv --out z --shard 1/2");
  EXPECT_NE(r.err.find("eval takes no --shard"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace binpick
