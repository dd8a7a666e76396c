// `binpick detect --picks` as a user runs it (docs/picks.md): OUT.picks.csv beside the results,
// a row per detection, the first pick on a part nothing lies on, the same bytes on a rerun, and
// bad grasps or gripper options refused with one message; a point cloud's picks the same way.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tests/support/cli_run.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  for (std::istringstream in(line); std::getline(in, cell, ',');) out.push_back(cell);
  return out;
}

std::vector<double> numbers(const std::string& cell) {
  std::vector<double> out;
  std::istringstream in(cell);
  for (double v; in >> v;) out.push_back(v);
  return out;
}

// A first pick (f: its fields) takes a part nothing covers: the true instance nearest the
// detection's position (its results row) is right within a tenth of the diameter and at least
// 90 % visible, and the pick approaches downwards into the bin (the camera looks down it).
void expect_first_pick_on_a_free_part(const fs::path& d, const std::vector<std::string>& f,
                                      const std::string& result, const std::string& pick) {
  const int scene = std::stoi(f[0]);
  const auto t = numbers(fields(result)[5]);
  ASSERT_EQ(t.size(), 3u);
  ASSERT_EQ(numbers(f[6]).size(), 9u);
  const fs::path dir = d / "data" / "test" / fmt::format("{:06d}", scene);
  const auto gt = nlohmann::json::parse(test::slurp(dir / "scene_gt.json"))["0"];
  const auto info = nlohmann::json::parse(test::slurp(dir / "scene_gt_info.json"))["0"];
  double nearest = 1e30;
  std::size_t which = 0;
  for (std::size_t k = 0; k < gt.size(); ++k) {
    const auto& tk = gt[k]["cam_t_m2c"];
    const double dist = std::hypot(std::hypot(tk[0].get<double>() - t[0], tk[1].get<double>() - t[1]),
                                   tk[2].get<double>() - t[2]);
    if (dist < nearest) nearest = dist, which = k;
  }
  EXPECT_LT(nearest, 5.2) << result;  // the detection is right (a tenth of the diameter)
  EXPECT_GE(info[which]["visib_fract"].get<double>(), 0.9) << pick;
  EXPECT_GT(numbers(f[8])[2], 0.7) << pick;
}

class PicksCli : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::fresh_temp_dir("picks_cli"));
    const fs::path& d = *dir_;
    ASSERT_EQ(test::run_binpick("synth --model builtin:bracket --out " + (d / "data").string() +
                                " --bins 2 --objects 60 --width 800 --height 450 --seed 3").status, 0);
    ASSERT_EQ(test::run_binpick("train --model builtin:bracket --out " + (d / "b.ppfm").string()).status, 0);
  }
  static fs::path* dir_;
};
fs::path* PicksCli::dir_ = nullptr;

TEST_F(PicksCli, WritesAPickPerDetectionTheFirstOnAPartNothingLiesOn) {
  const fs::path& d = *dir_;
  const std::string args = "detect --model " + (d / "b.ppfm").string() + " --dataset " +
                           (d / "data").string() + " --out " + (d / "r.csv").string() + " --picks";
  const test::CliRun run = test::run_binpick(args);
  ASSERT_EQ(run.status, 0) << run.err;
  const std::vector<std::string> picks = lines(test::slurp(d / "r.picks.csv"));
  const std::vector<std::string> results = lines(test::slurp(d / "r.csv"));
  ASSERT_EQ(picks.front(),
            "scene_id,im_id,obj_id,rank,order,grasp,R,t,approach,width,clearance,score,gripper,reason");
  ASSERT_EQ(picks.size(), results.size());  // a row per detection
  int first = 0;
  for (std::size_t i = 1; i < picks.size(); ++i) {
    const auto f = fields(picks[i]);
    ASSERT_GE(f.size(), 16u) << picks[i];  // the gripper's text holds 3 commas
    EXPECT_EQ(f[12] + "," + f[13] + "," + f[14] + "," + f[15], "\"suction:5.2,5.2,5.2,104\"")
        << "the default tool: the grasps' cup";
    if (f[4].empty()) {
      EXPECT_EQ(picks[i].back(), '"') << "a detection without a pick says why: " << picks[i];
      continue;
    }
    if (f[4] != "1") continue;
    ++first;
    expect_first_pick_on_a_free_part(d, f, results[i], picks[i]);
  }
  EXPECT_EQ(first, 2);  // a first pick in each image
  // eval judges them at the true poses: both succeed (the floor of this fixed-seed bin).
  const test::CliRun eval = test::run_binpick("eval --dataset " + (d / "data").string() +
                                              " --results " + (d / "r.csv").string() + " --out " +
                                              (d / "eval").string() + " --pictures 1 --no-vsd");
  ASSERT_EQ(eval.status, 0) << eval.err;
  EXPECT_NE(eval.out.find("picks: the first pick succeeds in 2 of 2 images (100.0 %)"),
            std::string::npos) << eval.out;
  // The report pictures the first image's pick and says it succeeds.
  EXPECT_TRUE(fs::is_regular_file(d / "eval/pictures/d0_000000_000000_picks.png"));
  const std::string html = test::slurp(d / "eval/report.html");
  EXPECT_NE(html.find("src=\"pictures/d0_000000_000000_picks.png\""), std::string::npos);
  EXPECT_NE(html.find(": succeeds."), std::string::npos);
  // A rerun finds every scene done and writes the same picks.
  ASSERT_EQ(test::run_binpick(args).status, 0);
  EXPECT_EQ(lines(test::slurp(d / "r.picks.csv")), picks);
}

TEST_F(PicksCli, ACloudGetsItsPicksToo) {
  // A bin's visible cloud as synth writes it, the bin itself not rendered (a cloud's bin is not
  // looked for: the rim would be taken for brackets): picks planned against the cloud seen
  // through the virtual camera, written beside the results as for a depth image.
  const fs::path d = *dir_ / "cloud";
  ASSERT_EQ(test::run_binpick("synth --model builtin:bracket --out " + (d / "data").string() +
                              " --bins 1 --objects 60 --width 800 --height 450 --seed 3 "
                              "--bin-render none").status, 0);
  const fs::path cloud = d / "data" / "test" / "000000" / "cloud" / "000000.ply";
  const test::CliRun run = test::run_binpick("detect --model " + (*dir_ / "b.ppfm").string() +
                                             " --cloud " + cloud.string() + " --out " +
                                             (d / "c.csv").string() + " --picks");
  ASSERT_EQ(run.status, 0) << run.err;
  const std::vector<std::string> picks = lines(test::slurp(d / "c.picks.csv"));
  const std::vector<std::string> results = lines(test::slurp(d / "c.csv"));
  ASSERT_EQ(picks.front(),
            "scene_id,im_id,obj_id,rank,order,grasp,R,t,approach,width,clearance,score,gripper,reason");
  ASSERT_EQ(picks.size(), results.size());
  int first = 0, refused = 0;
  for (std::size_t i = 1; i < picks.size(); ++i) {
    const auto f = fields(picks[i]);
    ASSERT_GE(f.size(), 16u) << picks[i];
    if (f[4].empty()) ++refused;
    if (f[4] != "1") continue;
    ++first;
    expect_first_pick_on_a_free_part(d, f, results[i], picks[i]);
  }
  EXPECT_EQ(first, 1);
  EXPECT_GT(refused, 0) << "a part standing on its edge is refused here too";
}

TEST_F(PicksCli, BadGraspsOrGripperAreOneMessage) {
  const fs::path& d = *dir_;
  const std::string base = "detect --model " + (d / "b.ppfm").string() + " --dataset " +
                           (d / "data").string() + " --out " + (d / "bad.csv").string();
  std::ofstream(d / "g.json") << R"({"suction": [{"point": [0, 0], "approach": [0, 0, 1], "cup_diameter": 5}]})";
  for (const auto& [option, message] :
       std::vector<std::pair<std::string, std::string>>{
           {"--grasps " + (d / "g.json").string(), "suction grasp 0: \"point\" (3 numbers) expected"},
           {"--grasps " + (d / "none.json").string(), "none.json"},
           {"--gripper suction:10,5", "four positive sizes"},
           {"--approach-cone 120", "approach-cone"}}) {
    const test::CliRun run = test::run_binpick(base + " " + option);
    EXPECT_EQ(run.status, 2) << option;
    EXPECT_NE(run.err.find(message), std::string::npos) << option << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(fs::exists(d / "bad.picks.csv"));
  }
}

}  // namespace
