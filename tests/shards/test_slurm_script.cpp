// The Slurm job array script of `--slurm` without a cluster: the array indices of the shards to
// run (all, or only the missing ones on a rerun), each task's --shard, the options as #SBATCH
// lines, arguments quoted for the shell, and the sharding options taken out of the command.
#include <gtest/gtest.h>

#include "host/core/error.hpp"
#include "host/shards/slurm_script.hpp"

namespace binpick {
namespace {

TEST(SlurmScript, ArraySpecJoinsRanges) {
  EXPECT_EQ(array_spec({0, 1, 2, 3}), "0-3");
  EXPECT_EQ(array_spec({3, 1}), "1,3");
  EXPECT_EQ(array_spec({0, 2, 3, 4, 7}), "0,2-4,7");
}

TEST(SlurmScript, RunsTheCommandWithEachTasksShard) {
  SlurmOptions o;
  o.tasks = 4;
  o.partition = "batch";
  o.time = "10:00";
  o.cpus_per_task = 2;
  const SlurmJob job{"detect", {"/opt/binpick", "detect", "--out", "it's.csv"}, {1, 3},
                     "/data/out.csv.parts/slurm", "/data"};
  const std::string s = sbatch_script(job, o);
  EXPECT_EQ(s.rfind("#!/bin/sh\n", 0), 0u);
  for (const char* line :
       {"#SBATCH --job-name=binpick-detect\n", "#SBATCH --array=1,3\n",
        "#SBATCH --output=/data/out.csv.parts/slurm/task_%a.log\n", "#SBATCH --chdir=/data\n",
        "#SBATCH --partition=batch\n", "#SBATCH --time=10:00\n", "#SBATCH --cpus-per-task=2\n",
        "exec '/opt/binpick' 'detect' '--out' 'it'\\''s.csv' --shard \"$((SLURM_ARRAY_TASK_ID + 1))/4\"\n"})
    EXPECT_NE(s.find(line), std::string::npos) << line << "\n" << s;
  EXPECT_EQ(s.find("--mem"), std::string::npos);

  o.partition = "a b";  // would be cut at the space by Slurm
  EXPECT_THROW(sbatch_script(job, o), InputError);
  o.partition = "";
  EXPECT_THROW(sbatch_script({"detect", {"x"}, {}, "/l", "/w"}, o), InputError);
}

TEST(SlurmScript, TaskCommandDropsTheShardingOptions) {
  const std::vector<std::string> argv{"/b", "detect", "--slurm", "--tasks", "4", "--out", "o.csv",
                                      "--partition=p", "--time", "5:00", "--dry-run",
                                      "--cpus-per-task", "2", "--mem", "1G", "--shard", "1/2",
                                      "--hypotheses", "3"};
  EXPECT_EQ(task_command(argv), (std::vector<std::string>{"/b", "detect", "--out", "o.csv",
                                                          "--hypotheses", "3"}));
}

TEST(SlurmScript, OwnCommandLineIsThisProgram) {
  const auto argv = own_command_line();
  ASSERT_FALSE(argv.empty());
  EXPECT_NE(argv[0].find("test_slurm_script"), std::string::npos) << argv[0];
  EXPECT_EQ(argv[0].front(), '/');
}

}  // namespace
}  // namespace binpick
