// `--slurm`'s submit, follow, merge and resubmit logic without a cluster (the real one is
// tests/cluster/slurm_cluster_test.sh, root only): a fake `sbatch` on PATH runs the array's
// tasks at once with their SLURM_ARRAY_TASK_ID (all but those listed in FAKE_SBATCH_SKIP, as if
// cancelled) and a fake `squeue` knows no job, so the array is over when sbatch returns.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/shards/slurm_run.hpp"
#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

constexpr const char* kFakeSbatch = R"(#!/bin/sh
# fake sbatch --parsable SCRIPT: runs every task of the script's --array synchronously.
script=$2
spec=$(sed -n 's/^#SBATCH --array=//p' "$script")
for part in $(echo "$spec" | tr ',' ' '); do
  lo=${part%-*}; hi=${part#*-}
  i=$lo
  while [ "$i" -le "$hi" ]; do
    case " $FAKE_SBATCH_SKIP " in *" $i "*) ;; *) SLURM_ARRAY_TASK_ID=$i sh "$script" ;; esac
    echo "$i" >> "$FAKE_SBATCH_LOG"
    i=$((i + 1))
  done
done
echo 42
)";

class SlurmRun : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::fresh_temp_dir("slurm_run");
    fs::create_directories(dir_ / "bin");
    std::ofstream(dir_ / "bin" / "sbatch") << kFakeSbatch;
    std::ofstream(dir_ / "bin" / "squeue") << "#!/bin/sh\nexit 1\n";
    for (const char* p : {"sbatch", "squeue"})
      fs::permissions(dir_ / "bin" / p, fs::perms::owner_all, fs::perm_options::replace);
    old_path_ = std::getenv("PATH");
    ::setenv("PATH", (dir_ / "bin").string().append(":").append(old_path_).c_str(), 1);
    ::setenv("FAKE_SBATCH_LOG", (dir_ / "submitted").c_str(), 1);
  }
  void TearDown() override {
    ::setenv("PATH", old_path_.c_str(), 1);
    ::unsetenv("FAKE_SBATCH_SKIP");
    fs::remove_all(dir_);
  }
  // Items 0..4 in 3 shards; a task touches done_K for its shard K (1-based); item i is done when
  // its shard's file is there.
  ShardedBatch batch() {
    ShardedBatch b;
    b.state_dir = dir_ / "state";
    b.record = {"detect", dir_ / "out.csv", {0, 1, 2, 3, 4}, 3};
    b.done = [d = dir_](int item) { return fs::exists(d / fmt::format("done_{}", item % 3 + 1)); };
    b.merge = [] { return std::string("merged"); };
    return b;
  }
  std::vector<std::string> command() const {
    return {"/bin/sh", "-c", "k=${2%/*}; touch \"$0/done_$k\"", dir_.string()};
  }
  std::string submitted() {
    const std::string s = test::slurp(dir_ / "submitted");
    fs::remove(dir_ / "submitted");
    return s;
  }
  fs::path dir_;
  std::string old_path_;
};

TEST_F(SlurmRun, SubmitsFollowsMergesAndResubmitsOnlyWhatIsMissing) {
  SlurmOptions o;
  o.tasks = 3;
  ::setenv("FAKE_SBATCH_SKIP", "1", 1);  // task 1 (shard 2/3) cancelled
  std::ostringstream out;
  try {
    run_on_slurm(batch(), o, command(), out);
    FAIL() << "a missing shard must be an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("shards 2/3 ended without their work"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(submitted(), "0\n1\n2\n");
  EXPECT_NE(out.str().find("submitting shards 1/3, 2/3, 3/3"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("job 42;"), std::string::npos) << out.str();
  EXPECT_EQ(test::slurp(dir_ / "state" / "slurm" / "job_id"), "42\n");
  const std::string script = test::slurp(dir_ / "state" / "slurm" / "array.sh");
  EXPECT_NE(script.find("#SBATCH --array=0-2\n"), std::string::npos) << script;

  ::unsetenv("FAKE_SBATCH_SKIP");
  out.str("");
  run_on_slurm(batch(), o, command(), out);
  EXPECT_EQ(submitted(), "1\n");  // only the missing shard
  EXPECT_NE(out.str().find("submitting shards 2/3 "), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("merged"), std::string::npos) << out.str();

  out.str("");
  run_on_slurm(batch(), o, command(), out);  // nothing missing: merge only
  EXPECT_FALSE(fs::exists(dir_ / "submitted"));
  EXPECT_EQ(out.str(), "every shard is done\nmerged\n");
}

TEST_F(SlurmRun, DryRunSubmitsNothing) {
  SlurmOptions o;
  o.tasks = 3;
  o.dry_run = true;
  std::ostringstream out;
  run_on_slurm(batch(), o, command(), out);
  EXPECT_NE(out.str().find("#SBATCH --array=0-2\n"), std::string::npos) << out.str();
  EXPECT_FALSE(fs::exists(dir_ / "submitted"));
  EXPECT_FALSE(fs::exists(dir_ / "state"));
}

TEST_F(SlurmRun, WithoutSbatchSaysWhere) {
  ::setenv("PATH", "/nonexistent", 1);
  SlurmOptions o;
  o.tasks = 3;
  std::ostringstream out;
  try {
    run_on_slurm(batch(), o, command(), out);
    FAIL() << "no sbatch must be an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sbatch and squeue are not on PATH"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace binpick
