// `binpick bench` as a user runs it: --help, bad options refused before any work, and the quick
// run writing a report whose numbers are all there and plausible (not timed: values are only
// checked to be positive and consistent). The quick run is the benchmark's smoke run in ctest.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "tests/support/cli_run.hpp"

using binpick::test::fresh_temp_dir;
using binpick::test::run_binpick;
using binpick::test::slurp;
using nlohmann::json;
namespace fs = std::filesystem;

TEST(BenchCli, help_names_the_options) {
  const auto r = run_binpick("bench --help");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* opt : {"--out", "--bins", "--objects", "--repeats", "--ref-ratios", "--opencv",
                          "--quick", "--model", "--real-size"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(BenchCli, bad_options_fail_fast_with_one_message) {
  const fs::path dir = fresh_temp_dir("bench_bad");
  for (const char* args :
       {"--bins 0", "--repeats 0", "--ref-ratios 0.2,abc", "--ref-ratios 0", "--ref-ratios ''",
        "--objects -3", "--model builtin:nosuchpart", "--width 4", "--real-size 2064",
        "--real-size 8x8", "--real-size 100x100x3"}) {
    const auto r = run_binpick("bench --out " + dir.string() + " " + std::string(args));
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir / "bench.md")) << args;
  }
  fs::remove_all(dir);
}

TEST(BenchCli, quick_run_writes_a_complete_report_and_reuses_its_scenes) {
  const fs::path dir = fresh_temp_dir("bench_quick");
  const auto r = run_binpick("bench --quick --out " + dir.string());
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir / "bench.md"));
  const json j = json::parse(slurp(dir / "bench.json"));

  const auto& m = j.at("machine");
  for (const char* peak : {"stream_gb_s", "fma_gflop_s", "gather_mlookup_s"})
    EXPECT_GT(m.at(peak).get<double>(), 0) << peak;
  ASSERT_EQ(j.at("synth").size(), 1u);
  EXPECT_TRUE(j.at("synth").at(0).at("measured_now").get<bool>());
  EXPECT_GT(j.at("synth").at(0).at("physics_s").get<double>(), 0);
  EXPECT_GT(j.at("synth").at(0).at("render_s").get<double>(), 0);
  EXPECT_GT(j.at("train").at("points").get<int>(), 100);
  EXPECT_GT(j.at("train").at("ms").get<double>(), 0);

  ASSERT_EQ(j.at("detect").size(), 2u);  // 20 % and 2 %
  double pairs_20 = 0, pairs_2 = 0;
  for (const auto& d : j.at("detect")) {
    EXPECT_GT(d.at("hypotheses").get<int>(), 0);
    const auto& ms = d.at("ms_per_hypothesis");
    const double parts = ms.at("preparation").get<double>() + ms.at("hypotheses").get<double>() +
                         ms.at("voting").get<double>() + ms.at("clustering").get<double>();
    EXPECT_NEAR(parts, ms.at("total").get<double>(), 1e-6 * (1 + parts));
    EXPECT_GT(d.at("throughput").at("pair_features_per_s").get<double>(), 0);
    EXPECT_GT(d.at("throughput").at("votes_per_s").get<double>(), 0);
    const double pairs = d.at("work_per_hypothesis").at("pairs").get<double>();
    (d.at("ref_ratio").get<double>() == 0.2 ? pairs_20 : pairs_2) = pairs;
    const double top = d.at("precision").at("top").get<double>();
    EXPECT_GE(top, 0);
    EXPECT_LE(top, 1);
  }
  EXPECT_GT(pairs_20, 5 * pairs_2);  // ten times the reference points, about ten times the pairs
  // The same bins at the real sensor's size (half of it in --quick), at the defaults.
  const auto& real = j.at("real_size").at("detect");
  EXPECT_EQ(real.at("images").get<int>(), 1);
  EXPECT_EQ(real.at("ref_ratio").get<double>(), 0.2);
  EXPECT_GT(real.at("ms_per_image").get<double>(), 0);
  EXPECT_GT(real.at("hypotheses").get<int>(), 0);
  EXPECT_TRUE(fs::exists(dir / "dataset_real" / "test" / "000000" / "depth" / "000000.png"));

  ASSERT_EQ(j.at("scaling").size(), 4u);
  for (const auto& s : j.at("scaling")) {
    EXPECT_GE(s.at("points").size(), 2u) << s.at("name");
    EXPECT_TRUE(std::isfinite(s.at("exponent").get<double>()));
  }
  // The opencv section says whether it ran, and why not if not.
  const auto& cv = j.at("opencv");
  if (cv.at("ran").get<bool>()) {
    EXPECT_EQ(cv.at("sides").size(), 2u);
    EXPECT_GT(cv.at("sides").at(0).at("opencv_ms_per_crop").get<double>(), 0);
  } else {
    EXPECT_FALSE(cv.at("why_not").get<std::string>().empty());
  }

  // Again, without OpenCV: the scene is reused with its recorded times.
  const auto again = run_binpick("bench --quick --opencv off --out " + dir.string());
  ASSERT_EQ(again.status, 0) << again.err;
  const json k = json::parse(slurp(dir / "bench.json"));
  EXPECT_FALSE(k.at("synth").at(0).at("measured_now").get<bool>());
  EXPECT_EQ(k.at("synth").at(0).at("physics_s"), j.at("synth").at(0).at("physics_s"));
  EXPECT_FALSE(k.at("opencv").at("ran").get<bool>());
  fs::remove_all(dir);
}
