// detect --targets FILE (BOP's test_targets_bop19.json as the instance budget): each image gets
// exactly the rows of `--instances inst_count` on that image, images not listed (or listing
// another obj_id only) get none and are not read, and bad target files or --targets with
// --instances are refused with one message.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/formats/bop/results_csv.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

// The CSV lines of one scene, without the time column.
std::string scene_rows(const fs::path& csv, int scene) {
  std::string out;
  for (bop::ResultRow row : bop::read_results_csv(csv)) {
    row.time = 0;  // the image's seconds differ between runs
    if (row.scene_id == scene) out += bop::format_result_row(row) + "\n";
  }
  return out;
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

}  // namespace

TEST(DetectTargets, BudgetPerImageFromTheTargetList) {
  const fs::path dir = test::fresh_temp_dir("detect_targets");
  const std::string data = (dir / "data").string(), ppfm = (dir / "bracket.ppfm").string();
  auto r = test::run_binpick(fmt::format(
      "synth --model builtin:bracket --out {} --bins 2 --objects 35 --width 640 --height 360",
      data));
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(fmt::format("train --model builtin:bracket --out {}", ppfm));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto detect = [&](const std::string& name, const std::string& extra) {
    const fs::path csv = dir / name;
    const auto run = test::run_binpick(
        fmt::format("detect --model {} --dataset {} --out {} {}", ppfm, data, csv.string(), extra));
    EXPECT_EQ(run.status, 0) << extra << "\n" << run.err;
    return std::make_pair(csv, run.out);
  };

  // The dataset's own list (synth writes it): every image is a target of obj_id 1.
  const fs::path bop19 = fs::path(data) / "test_targets_bop19.json";
  std::map<int, int> count;
  for (const auto& e : nlohmann::json::parse(test::slurp(bop19)))
    count[e["scene_id"].get<int>()] = e["inst_count"].get<int>();
  ASSERT_EQ(count.size(), 2u);
  const auto [listed, listed_log] = detect("listed.csv", "--targets " + bop19.string());
  for (const auto& [scene, n] : count) {
    ASSERT_GT(n, 5) << "scene " << scene;  // more than the paper's 5 rows: the budget shows
    const auto [alone, log] =
        detect(fmt::format("alone{}.csv", scene), fmt::format("--instances {} --scenes {}", n, scene));
    EXPECT_FALSE(scene_rows(alone, scene).empty());
    EXPECT_EQ(scene_rows(listed, scene), scene_rows(alone, scene)) << "scene " << scene;
  }

  // A hand-made list: scene 1 only, 3 instances; scene 0 lists another object only.
  const fs::path mine = dir / "mine.json";
  write(mine, R"([{"scene_id": 0, "im_id": 0, "obj_id": 7, "inst_count": 2},
                  {"scene_id": 1, "im_id": 0, "obj_id": 1, "inst_count": 3}])");
  const auto [three, three_log] = detect("three.csv", "--targets " + mine.string());
  EXPECT_EQ(scene_rows(three, 0), "");
  const auto [alone3, log3] = detect("alone3.csv", "--instances 3 --scenes 1");
  EXPECT_EQ(scene_rows(three, 1), scene_rows(alone3, 1));
  EXPECT_LE(bop::read_results_csv(three).size(), 3u);
  EXPECT_NE(three_log.find("1 without a target not read"), std::string::npos) << three_log;

  // Refused with one message: each names what is wrong.
  write(dir / "bad.json", R"({"scene_id": 1})");
  write(dir / "huge.json", R"([{"scene_id": 1, "im_id": 0, "obj_id": 1, "inst_count": 5000}])");
  const std::pair<std::string, std::string> bad[] = {
      {"--targets " + (dir / "bad.json").string(), "bad.json"},
      {"--targets " + (dir / "huge.json").string(), "at most 1000"},
      {"--targets " + (dir / "none.json").string(), "none.json"},
      {"--targets " + bop19.string() + " --instances 4", "--instances"},
  };
  for (const auto& [args, says] : bad) {
    const auto run = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} {}",
                                                   ppfm, data, (dir / "x.csv").string(), args));
    EXPECT_EQ(run.status, 2) << args;
    EXPECT_NE(run.err.find(says), std::string::npos) << args << "\n" << run.err;
    EXPECT_FALSE(fs::exists(dir / "x.csv")) << args;
  }
  fs::remove_all(dir);
}
