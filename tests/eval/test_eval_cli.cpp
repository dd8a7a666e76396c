// `binpick eval` as a user runs it: a report from a dataset and its results, the JSON summary,
// and one clear message with exit status 2 (and no report) for each kind of bad input.
#include <gtest/gtest.h>

#include <fstream>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/formats/bop/bop_models.hpp"
#include "host/app/options/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;
using test::run_binpick;

const bop::Pose kPart{Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix(),
                      {10, -20, 700}};

// One 64 x 48 image over a floor at 800 mm with one part; enough for eval and its pictures.
void write_tiny_dataset(const fs::path& root) {
  fs::create_directories(root / "test/000000/depth");
  bop::write_camera(root / "camera.json", {80, 80, 32, 24, 64, 48, 1.0});
  write_bop_models(root, cli::load_part({"builtin:bracket", {}}).mesh, 1, {});
  bop::write_scene_gt(root / "test/000000/scene_gt.json", {{0, {{1, kPart}}}});
  bop::SceneCamera cam;
  cam.K << 80, 0, 32, 0, 80, 24, 0, 0, 1;
  bop::write_scene_cameras(root / "test/000000/scene_camera.json", {{0, cam}});
  GrayImage<std::uint16_t> depth{64, 48, std::vector<std::uint16_t>(64 * 48, 800)};
  for (int y = 18; y < 30; ++y)
    for (int x = 28; x < 40; ++x) depth.pixels[std::size_t(y) * 64 + std::size_t(x)] = 700;
  write_png(root / "test/000000/depth/000000.png", depth);
}

struct Fixture {
  fs::path dir = test::fresh_temp_dir("eval_cli");
  fs::path dataset = dir / "ds", results = dir / "results.csv", out = dir / "report";
  Fixture() {
    write_tiny_dataset(dataset);
    bop::ResultRow row;
    row.R = kPart.R, row.t = kPart.t + Eigen::Vector3d(0, 0, 1), row.score = 0.8, row.time = 0.2;
    bop::write_results_csv(results, {row});
  }
  std::string args(const fs::path& csv, const std::string& pictures = "1") const {
    return "eval --dataset '" + dataset.string() + "' --results '" + csv.string() + "' --out '" +
           out.string() + "' --pictures " + pictures;
  }
};

TEST(EvalCli, WritesTheReportAndPrintsTheSummary) {
  Fixture f;
  const auto r = run_binpick(f.args(f.results));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("wrote "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("100.0%"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("score: threshold 0.8 keeps 90 % of right poses (1 of 1); 0.0 % of the "
                       "poses it accepts are wrong (0 of 1)\n"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.err, "");
  for (const char* name : {"report.html", "report.json", "curves.csv", "score_curves.csv",
                           "hypotheses.csv", "precision.png", "score_threshold.png",
                           "pictures/d0_000000_000000_detections.png"})
    EXPECT_GT(fs::file_size(f.out / name), 0u) << name;

  const auto j = run_binpick(f.args(f.results) + " --json");
  ASSERT_EQ(j.status, 0) << j.err;
  const auto json = nlohmann::json::parse(j.out);
  EXPECT_EQ(json["datasets"][0]["hypotheses"].get<int>(), 1);
  EXPECT_DOUBLE_EQ(json["datasets"][0]["precision"]["strict"]["top"].get<double>(), 1.0);
  EXPECT_NEAR(json["datasets"][0]["ms_per_hypothesis"].get<double>(), 200.0, 1e-9);
  EXPECT_DOUBLE_EQ(
      json["datasets"][0]["score_calibration"]["loose"]["threshold"].get<double>(), 0.8);
}

// Results of an older detect hold vote counts: still a report (exit 0), with a warning that
// names the problem, and no score plot.
TEST(EvalCli, VoteCountScoresAreAWarning) {
  Fixture f;
  bop::ResultRow row;
  row.R = kPart.R, row.t = kPart.t, row.score = 4211, row.time = 0.2;
  bop::write_results_csv(f.dir / "votes.csv", {row});
  const auto r = run_binpick(f.args(f.dir / "votes.csv"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("binpick: warning: ds: 1 of 1 scores are outside [0, 1] (highest 4211)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("score: threshold 4211 keeps 90 % of right poses (1 of 1)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("[scores not in [0, 1]]"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(f.out / "score_threshold.png"));
  EXPECT_GT(fs::file_size(f.out / "score_curves.csv"), 0u);
}

// Exit status 2, the message on stderr, and nothing written under --out.
void expect_rejected(const Fixture& f, const std::string& args, const std::string& message) {
  const auto r = run_binpick(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(f.out / "report.html"));
  EXPECT_FALSE(fs::exists(f.out / "report.json"));
}

TEST(EvalCli, BadInputIsExitStatusTwoWithoutAReport) {
  Fixture f;
  expect_rejected(f, f.args(f.dir / "missing.csv"), "missing.csv");

  bop::ResultRow elsewhere;
  elsewhere.scene_id = 5;
  bop::write_results_csv(f.dir / "elsewhere.csv", {elsewhere});
  expect_rejected(f, f.args(f.dir / "elsewhere.csv"), "scene 5 image 0");

  std::ofstream(f.dir / "malformed.csv") << "scene_id,im_id,obj_id,score,R,t,time\n0,0,1,3,1 0 0,0 0 0,1\n";
  expect_rejected(f, f.args(f.dir / "malformed.csv"), "malformed.csv");

  expect_rejected(f, f.args(f.results) + " --dataset '" + f.dataset.string() + "'", "1 --results");
  expect_rejected(f, "eval --dataset '" + (f.dir / "nowhere").string() + "' --results '" +
                         f.results.string() + "' --out '" + f.out.string() + "'",
                  "nowhere");
  expect_rejected(f, f.args(f.results, "-1"), "--pictures");
  expect_rejected(f, f.args(f.results) + " --vsd-delta 0", "VSD delta 0 mm");
  expect_rejected(f, f.args(f.results) + " --vsd-delta inf", "VSD delta inf mm");
}

}  // namespace
}  // namespace binpick
