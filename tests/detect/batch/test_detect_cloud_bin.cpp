// `binpick detect --cloud` on a cloud that holds its bin (detector_cloud.cpp): the bin is found
// on the cloud's virtual depth image as on a sensor's, so its rim and walls are kept out of the
// highest points and crops. Without the region (--bin none) the rim, the highest thing in view,
// is taken for brackets: the test can fail. Picks plan against the bin found. A bin of a given
// size (--bin W,D,H) and --roi apply to a cloud too.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/formats/bop/results_csv.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

class DetectCloudBin : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::fresh_temp_dir("detect_cloud_bin"));
    ASSERT_EQ(test::run_binpick("train --model builtin:bracket --out " + model()).status, 0);
    // The bin rendered (synth's default): its rim stands 300 mm over the floor, far above a
    // 60-bracket pile.
    ASSERT_EQ(test::run_binpick("synth --model builtin:bracket --out " + (*dir_ / "data").string() +
                                " --bins 1 --objects 60 --width 800 --height 450 --seed 3")
                  .status,
              0);
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(*dir_, ec);
    delete dir_;
  }
  static std::string model() { return (*dir_ / "b.ppfm").string(); }
  static fs::path scene() { return *dir_ / "data" / "test" / "000000"; }

  // detect --cloud with extra options: its run and the distance (mm) of its top-ranked pose's
  // translation from the nearest true bracket's.
  static std::pair<test::CliRun, double> detect(const std::string& options) {
    const fs::path out = *dir_ / fmt::format("r{}.csv", runs_++);
    const test::CliRun run = test::run_binpick("detect --model " + model() + " --cloud " +
                                               (scene() / "cloud" / "000000.ply").string() +
                                               " --out " + out.string() + " --verbose " + options);
    if (run.status != 0) return {run, -1};
    const auto rows = bop::read_results_csv(out);
    if (rows.empty()) return {run, -1};
    const auto gt = nlohmann::json::parse(test::slurp(scene() / "scene_gt.json"))["0"];
    double nearest = 1e30;
    for (const auto& g : gt) {
      const auto& t = g["cam_t_m2c"];
      nearest = std::min(nearest, (rows[0].t - Eigen::Vector3d(t[0], t[1], t[2])).norm());
    }
    return {run, nearest};
  }
  static double diameter() {
    return nlohmann::json::parse(test::slurp(*dir_ / "data" / "synth.json"))["diameter_mm"];
  }

  static fs::path* dir_;
  static int runs_;
};
fs::path* DetectCloudBin::dir_ = nullptr;
int DetectCloudBin::runs_ = 0;

TEST_F(DetectCloudBin, TheBinIsFoundAndItsRimIsNotTakenForAPart) {
  const auto [found, near_found] = detect("");
  ASSERT_EQ(found.status, 0) << found.err;
  EXPECT_NE(found.out.find("a bin found in 1 of 1 images"), std::string::npos) << found.out;
  // The built-in bin's interior, 600 x 400 x 300 mm, within a centimetre.
  const auto at = found.out.find("bin: interior ");
  ASSERT_NE(at, std::string::npos) << found.out;
  double w = 0, d = 0, h = 0;
  std::string x;
  std::istringstream(found.out.substr(at + 14)) >> w >> x >> d >> x >> h;
  EXPECT_NEAR(w, 600, 10);
  EXPECT_NEAR(d, 400, 10);
  EXPECT_NEAR(h, 300, 10);
  EXPECT_LT(near_found, 0.1 * diameter()) << "the top-ranked pose is on no bracket";

  // Picks plan against the bin found: one first pick, on a row of its own.
  const auto [picked, near_picked] = detect("--picks");
  ASSERT_EQ(picked.status, 0) << picked.err;
  EXPECT_EQ(near_picked, near_found);
  const std::string picks = test::slurp(*dir_ / fmt::format("r{}.picks.csv", runs_ - 1));
  std::size_t firsts = 0, rows = 0;
  std::istringstream in(picks);
  std::string line;
  std::getline(in, line);  // header
  for (; std::getline(in, line); ++rows) {
    std::vector<std::string> f;
    std::istringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');) f.push_back(c);
    ASSERT_GE(f.size(), 5u) << line;
    firsts += f[4] == "1";
  }
  EXPECT_GT(rows, 0u);
  EXPECT_EQ(firsts, 1u) << picks;

  const auto [none, near_none] = detect("--bin none");
  ASSERT_EQ(none.status, 0) << none.err;
  EXPECT_GT(near_none, 0.5 * diameter()) << "without the bin the rim should have been taken";
}

TEST_F(DetectCloudBin, ASizedBinAndARegionApplyToACloud) {
  const auto [sized, near_sized] = detect("--bin 600,400,300");
  ASSERT_EQ(sized.status, 0) << sized.err;
  EXPECT_NE(sized.out.find("bin: interior "), std::string::npos) << sized.out;
  EXPECT_LT(near_sized, 0.1 * diameter());
  // A camera-frame box far off the bin keeps nothing of the cloud: one clear message.
  const auto [roi, near_roi] = detect("--bin none --roi camera:5000,5000,5000,5100,5100,5100");
  EXPECT_EQ(roi.status, 2) << roi.err;
  EXPECT_NE(roi.err.find("no point of the cloud lies in the region"), std::string::npos) << roi.err;
}

}  // namespace
