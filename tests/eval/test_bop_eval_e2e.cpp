// BOP's recalls end to end: synth a bin, detect with an instance budget, `binpick eval --json`.
// The average recalls are fractions, and they agree with the paper's figures: every pose right
// at 5 % / 5 degrees is within 0.1 d in MSSD (0.05 d of translation plus a 5 degree turn moves no
// vertex by more than 0.05 d + 2 sin(2.5 deg) d), so MSSD recall at 0.10 counts at least those.
// With BOP_TOOLKIT set to a checkout of thodan/bop_toolkit, tools/bop_toolkit_check.py also
// compares the numbers with the toolkit's own functions.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

TEST(BopEvalE2e, AverageRecallsAreFractionsConsistentWithThePapersFigures) {
  const fs::path dir = test::fresh_temp_dir("bop_eval_e2e");
  const std::string data = (dir / "data").string(), ppfm = (dir / "shaft.ppfm").string();
  const std::string csv = (dir / "ten.csv").string(), out = (dir / "report").string();
  auto r = test::run_binpick(fmt::format(
      "synth --model builtin:shaft --out {} --bins 1 --objects 20 --width 640 --height 360 "
      "--noise 0.01",
      data));
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(fmt::format("train --model builtin:shaft --out {}", ppfm));
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(
      fmt::format("detect --model {} --dataset {} --out {} --instances 10", ppfm, data, csv));
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(
      fmt::format("eval --dataset {} --results {} --out {} --pictures 0 --json", data, csv, out));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto report = nlohmann::json::parse(r.out);
  const auto& d = report["datasets"][0];
  const auto& bop = d["bop"];

  const int targets = bop["targets"].get<int>();
  EXPECT_GT(targets, 10);  // most of the 20 parts are at least 10 % visible
  EXPECT_GT(bop["estimates"].get<int>(), 0);
  EXPECT_LE(bop["estimates"].get<int>(), 10);
  for (const char* key : {"ar", "ar_vsd", "ar_mssd", "ar_mspd"}) {
    EXPECT_GE(bop[key].get<double>(), 0.0) << key;
    EXPECT_LE(bop[key].get<double>(), 1.0) << key;
  }
  EXPECT_NEAR(bop["ar"].get<double>(),
              (bop["ar_vsd"].get<double>() + bop["ar_mssd"].get<double>() +
               bop["ar_mspd"].get<double>()) / 3.0, 1e-12);
  ASSERT_EQ(bop["vsd"]["recall"].size(), 10u);  // one curve per tau
  EXPECT_GT(bop["vsd"]["renders"].get<int>(), 0);
  const auto mssd = bop["mssd"]["recall"].get<std::vector<double>>();
  ASSERT_EQ(mssd.size(), 10u);
  for (std::size_t k = 1; k < mssd.size(); ++k) EXPECT_GE(mssd[k], mssd[k - 1]);
  ASSERT_EQ(bop["objects"].size(), 1u);
  EXPECT_DOUBLE_EQ(bop["objects"][0]["ar_mssd"].get<double>(), bop["ar_mssd"].get<double>());

  const std::size_t hypotheses = d["hypotheses"].get<std::size_t>();
  const double strict_right = d["precision"]["strict"]["all"].get<double>() * double(hypotheses);
  EXPECT_GT(strict_right, 0.5 * double(hypotheses));  // the shaft is found
  EXPECT_GE(mssd[1] * targets + 1e-9, strict_right);

  // The printed summary has the BOP line next to the paper's table.
  r = test::run_binpick(
      fmt::format("eval --dataset {} --results {} --out {} --pictures 0", data, csv, out));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("BOP: AR_VSD "), std::string::npos) << r.out;
  EXPECT_NE(test::slurp(fs::path(out) / "report.html").find("BOP average recall"),
            std::string::npos);

  // Without VSD: no rendering, AR of the two others.
  r = test::run_binpick(fmt::format(
      "eval --dataset {} --results {} --out {} --pictures 0 --json --no-vsd", data, csv, out));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto no_vsd = nlohmann::json::parse(r.out)["datasets"][0]["bop"];
  EXPECT_TRUE(no_vsd["ar_vsd"].is_null());
  EXPECT_TRUE(no_vsd["vsd"].is_null());
  EXPECT_NEAR(no_vsd["ar"].get<double>(),
              (bop["ar_mssd"].get<double>() + bop["ar_mspd"].get<double>()) / 2.0, 1e-12);

  if (const char* toolkit = std::getenv("BOP_TOOLKIT")) {
    const std::string cmd = fmt::format(
        "python3 '{}/tools/bop_toolkit_check.py' --toolkit '{}' --dataset '{}' --results '{}' "
        "--report '{}/report.json' > '{}/check.txt' 2>&1",
        BINPICK_SOURCE_DIR, toolkit, data, csv, out, dir.string());
    const int status = std::system(cmd.c_str());
    const std::string check = test::slurp(dir / "check.txt");
    if (WIFEXITED(status) && WEXITSTATUS(status) == 77) GTEST_SKIP() << check;
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << check;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace binpick
