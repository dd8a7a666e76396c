// `binpick run` as a user runs it: two noise levels of tiny bins give one report (report.html,
// report.json, precision.png, curves.csv: one curve per noise level; score_threshold.png,
// score_curves.csv), the results and the final table with its score column; the same command
// again resumes (bins, model and detections reused). Bad options exit 2
// with one message and make nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/formats/bop/results_csv.hpp"
#include "host/tune/experiment.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

// The distinct labels (first column) of curves.csv.
std::set<std::string> curve_labels(const std::string& csv) {
  std::set<std::string> labels;
  std::size_t start = csv.find('\n') + 1;  // after the header
  while (start < csv.size()) {
    const std::size_t end = csv.find('\n', start);
    const std::string line = csv.substr(start, end - start);
    if (!line.empty()) labels.insert(line.substr(0, line.find("\",") + 1));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return labels;
}

}  // namespace

TEST(RunCli, MakesOneReportWithACurvePerNoiseLevelAndResumes) {
  const fs::path dir = test::fresh_temp_dir("run_cli");
  const fs::path out = dir / "exp";
  const std::string cmd = fmt::format(
      "run --model builtin:bracket --out {} --bins 2 --objects 20 --noise 0,0.02 --width 640 "
      "--height 360 --pictures 1 --ref-ratio 0.05",
      out.string());
  auto r = test::run_binpick(cmd);
  ASSERT_EQ(r.status, 0) << r.out << r.err;

  for (const char* file : {"report.html", "report.json", "precision.png", "curves.csv",
                           "score_curves.csv", "score_threshold.png"})
    EXPECT_GT(fs::file_size(out / "report" / file), 0u) << file;
  EXPECT_EQ(curve_labels(test::slurp(out / "report" / "curves.csv")).size(), 2u);
  const auto json = nlohmann::json::parse(test::slurp(out / "report" / "report.json"));
  ASSERT_EQ(json["datasets"].size(), 2u);
  EXPECT_DOUBLE_EQ(json["datasets"][0]["noise"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(json["datasets"][1]["noise"].get<double>(), 0.02);
  for (const char* noise : {"noise_0.00", "noise_0.02"}) {
    EXPECT_TRUE(fs::is_directory(out / noise / "test" / "000001")) << noise;
    EXPECT_FALSE(bop::read_results_csv(out / "results" / (std::string(noise) + ".csv")).empty());
  }
  EXPECT_TRUE(fs::is_regular_file(out / "model.ppfm"));
  // The same results named as the BOP toolkit parses them (METHOD_DATASET-SPLIT.csv), and each
  // dataset under that DATASET name in OUT/bop.
  for (const auto& [noise, name] : {std::pair{"noise_0.00", "noise000"}, {"noise_0.02", "noise002"}}) {
    const fs::path toolkit = out / "results" / fmt::format("binpick_{}-test.csv", name);
    EXPECT_EQ(test::slurp(toolkit), test::slurp(out / "results" / (std::string(noise) + ".csv")))
        << toolkit;
    const fs::path link = out / "bop" / name;
    EXPECT_TRUE(fs::is_symlink(link)) << link;
    EXPECT_EQ(fs::read_symlink(link), fs::path("..") / noise) << link;
    EXPECT_TRUE(fs::is_regular_file(link / "test" / "000001" / "scene_gt.json")) << link;
  }
  // The final table: a heading with both operating points and one row per noise level.
  EXPECT_NE(r.out.find("loose 10%/15deg"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("strict 5%/5deg"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ms/hyp"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n      0     2 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n   0.02     2 "), std::string::npos) << r.out;
  // The score column (wrong fraction at the threshold keeping 90 % of right poses) lines up:
  // its header ends where each row's cell ends, and the rows are as long as the header.
  const std::size_t header = r.out.find("\n  noise ");
  ASSERT_NE(header, std::string::npos) << r.out;
  const std::string header_line =
      r.out.substr(header + 1, r.out.find('\n', header + 1) - header - 1);
  ASSERT_NE(header_line.find("wrong@90%"), std::string::npos) << header_line;
  const std::size_t wrong_end = header_line.find("wrong@90%") + 9;
  for (const char* row_start : {"\n      0     2 ", "\n   0.02     2 "}) {
    const std::size_t at = r.out.find(row_start) + 1;
    const std::string row = r.out.substr(at, r.out.find('\n', at) - at);
    EXPECT_EQ(row.size(), header_line.size()) << row << "\n" << header_line;
    const char last = row[wrong_end - 1];
    EXPECT_TRUE(last == '%' || last == '-') << row << "\n" << header_line;
    EXPECT_EQ(row[wrong_end], ' ') << row;
  }
  EXPECT_NE(r.out.find((out / "report" / "report.html").string()), std::string::npos) << r.out;

  const std::string results = test::slurp(out / "results" / "noise_0.02.csv");
  r = test::run_binpick(cmd);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("0 bins made, 2 already there"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("reused"), std::string::npos) << r.out;
  EXPECT_EQ(test::slurp(out / "results" / "noise_0.02.csv"), results);  // not detected again
  EXPECT_EQ(test::slurp(out / "results" / "binpick_noise002-test.csv"), results);
  EXPECT_EQ(r.err.find("left as it is"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("left as it is"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

TEST(RunCli, ToolkitDatasetNamesHoldNoSeparator) {
  EXPECT_EQ(bop_dataset_name(0.0), "noise000");
  EXPECT_EQ(bop_dataset_name(0.02), "noise002");
  EXPECT_EQ(bop_dataset_name(0.05), "noise005");
  EXPECT_EQ(bop_dataset_name(0.005), "noise0005");
  EXPECT_EQ(bop_dataset_name(0.1), "noise010");
  EXPECT_EQ(bop_dataset_name(1.0), "noise100");
  EXPECT_EQ(toolkit_results_name(0.02), "binpick_noise002-test.csv");
  // As the toolkit reads it: name.split('.')[0].split('_') -> method, DATASET-SPLIT.
  std::set<std::string> seen;
  for (double n : {0.0, 0.001, 0.01, 0.015, 0.1, 0.105, 0.5, 1.0}) {
    const std::string name = toolkit_results_name(n);
    const std::string stem = name.substr(0, name.find('.'));
    ASSERT_EQ(std::count(stem.begin(), stem.end(), '_'), 1) << name;
    const std::string rest = stem.substr(stem.find('_') + 1);
    ASSERT_EQ(std::count(rest.begin(), rest.end(), '-'), 1) << name;
    EXPECT_EQ(rest.substr(0, rest.find('-')), bop_dataset_name(n));
    EXPECT_EQ(rest.substr(rest.find('-') + 1), "test");
    EXPECT_TRUE(seen.insert(bop_dataset_name(n)).second) << n;
  }
}

TEST(RunCli, BadOptionsExit2WithOneMessage) {
  const fs::path dir = test::fresh_temp_dir("run_bad");
  const std::string out = (dir / "exp").string();
  for (const std::string args :
       {"--model builtin:bracket --noise ''", "--model builtin:bracket --noise 0,0",
        "--model builtin:bracket --noise 0,-0.01", "--model builtin:nosuch",
        "--model builtin:bracket --bins 0", "--model builtin:bracket --hypotheses -1",
        "--model builtin:bracket --params /nonexistent.json",
        "--model builtin:bracket --distractors builtin:bolt:1.5",
        "--model builtin:bracket --distractors builtin:nosuch",
        "--model builtin:bracket --camera-tilt 95", "--model builtin:bracket --bin-render some",
        "--model builtin:bracket --sensor-model structured-light --grazing-limit nan"}) {
    const auto r = test::run_binpick("run " + args + " --out " + out);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("binpick: error: "), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

// Each bin's pile is simulated once for all noise levels (synth/pile_cache.hpp): the second
// level says it reused the pile, and its files are byte for byte those `synth` makes alone.
TEST(RunCli, SimulatesEachPileOnceForAllNoiseLevels) {
  const fs::path dir = test::fresh_temp_dir("run_piles");
  const std::string common =
      "--model builtin:bolt --bins 2 --objects 15 --width 320 --height 180 --seed 4";
  auto r = test::run_binpick(
      fmt::format("run {} --noise 0,0.03 --out {}", common, (dir / "exp").string()));
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const std::string said = r.out + r.err;
  EXPECT_NE(said.find("physics reused (the pile of an earlier noise level)"), std::string::npos)
      << said;
  r = test::run_binpick(
      fmt::format("synth {} --noise 0.03 --out {}", common, (dir / "alone").string()));
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  for (const char* file : {"scene_gt.json", "scene_gt_info.json", "depth/000000.png"})
    for (const char* scene : {"000000", "000001"}) {
      const fs::path in_run = dir / "exp" / "noise_0.03" / "test" / scene / file;
      const fs::path alone = dir / "alone" / "test" / scene / file;
      EXPECT_EQ(test::slurp(in_run), test::slurp(alone)) << in_run;
      EXPECT_GT(fs::file_size(alone), 0u) << alone;
    }
}
