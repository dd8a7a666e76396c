// `binpick train` end to end: a built-in part becomes a .ppfm file that loads, with the
// symmetries found on it; bad options exit non-zero with one message on stderr and leave no
// output file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "host/train/ppf_model_file.hpp"
#include "tests/support/cli_run.hpp"

namespace fs = std::filesystem;
using binpick::test::CliRun;
using binpick::test::slurp;

namespace {

CliRun run(const std::string& args) { return binpick::test::run_binpick(args); }

class TrainCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = binpick::test::fresh_temp_dir("train_cli"); }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

}  // namespace

TEST_F(TrainCli, HelpDocumentsEveryOption) {
  const CliRun r = run("train --help");
  for (const char* opt : {"--model", "--out", "--voxel-ratio", "--distance-steps", "--angle-steps",
                          "--unit-scale", "--diameter"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt << "\n" << r.out;
}

TEST_F(TrainCli, TrainsTheBuiltinBolt) {
  const fs::path model = dir_ / "bolt.ppfm";
  const CliRun r = run("train --model builtin:bolt --out " + model.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("model points"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("distinct keys"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("symmetry: 5 discrete: 6-fold about (0, 0, 1)\n"), std::string::npos) << r.out;
  const binpick::PpfModel m = binpick::read_ppf_model(model);
  EXPECT_EQ(m.symmetries.discrete.size(), 5u);  // the hex head's turns
  EXPECT_GT(m.cloud.points.size(), 50u);
  EXPECT_EQ(m.table.entries.size(), m.cloud.points.size() * (m.cloud.points.size() - 1));
  EXPECT_NEAR(m.voxel_size, 0.05f * m.diameter, 1e-4f);
  // Deterministic: a second run writes the same bytes.
  const fs::path again = dir_ / "again.ppfm";
  ASSERT_EQ(run("train --model builtin:bolt --out " + again.string()).status, 0);
  EXPECT_EQ(slurp(model), slurp(again));
}

TEST_F(TrainCli, BadOptionsFailWithAMessageAndNoFile) {
  const fs::path model = dir_ / "bad.ppfm";
  for (const std::string bad :
       {"--voxel-ratio nan", "--voxel-ratio 0", "--voxel-ratio -0.05", "--voxel-ratio 2",
        "--distance-steps 0", "--distance-steps 1000000", "--distance-steps -3",
        "--angle-steps 0", "--angle-steps 1000000", "--angle-steps x"}) {
    const CliRun r = run("train --model builtin:bolt --out " + model.string() + " " + bad);
    EXPECT_NE(r.status, 0) << bad;
    EXPECT_FALSE(r.err.empty()) << bad;
    EXPECT_FALSE(fs::exists(model)) << bad;
  }
  const CliRun missing = run("train --model builtin:bolt");
  EXPECT_NE(missing.status, 0);
  EXPECT_NE(missing.err.find("--out"), std::string::npos) << missing.err;
  const CliRun nodir = run("train --model builtin:bolt --out " + (dir_ / "no/such/dir.ppfm").string());
  EXPECT_EQ(nodir.status, 2) << nodir.err;
  const CliRun unknown = run("train --model builtin:no_such_part --out " + model.string());
  EXPECT_EQ(unknown.status, 2) << unknown.err;
  EXPECT_FALSE(fs::exists(model));
}
