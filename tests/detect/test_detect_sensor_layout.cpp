// `binpick detect` and `binpick eval` on a dataset in the layout of BOP's industrial datasets:
// another split, every file with the sensor's suffix, several images per scene with ids other
// than 0. The results must be those of the plain layout, row for row.
#include <gtest/gtest.h>

#include <string>

#include <fmt/format.h>

#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

// The plain dataset's scene 0, image 0, as images 3 and 8 of scene 5 of split "val" with the
// sensor suffix "photoneo" (both images the same picture).
void copy_as_sensor_layout(const fs::path& plain, const fs::path& out) {
  const fs::path from = plain / "test/000000", to = out / "val/000005";
  fs::create_directories(to / "depth_photoneo");
  fs::copy(plain / "models", out / "models", fs::copy_options::recursive);
  const auto cam = bop::read_scene_cameras(from / "scene_camera.json").at(0);
  const auto gt = bop::read_scene_gt(from / "scene_gt.json").at(0);
  bop::write_scene_cameras(to / "scene_camera_photoneo.json", {{3, cam}, {8, cam}});
  bop::write_scene_gt(to / "scene_gt_photoneo.json", {{3, gt}, {8, gt}});
  for (const char* id : {"000003.png", "000008.png"})
    fs::copy(from / "depth/000000.png", to / "depth_photoneo" / id);
}

TEST(DetectSensorLayout, ReadsSuffixedFilesOfAnotherSplit) {
  const fs::path dir = test::fresh_temp_dir("detect_sensor_layout");
  const std::string plain = (dir / "plain").string(), ppfm = (dir / "bolt.ppfm").string();
  auto r = test::run_binpick(fmt::format(
      "synth --model builtin:bolt --out {} --bins 1 --objects 6 --width 320 --height 180 "
      "--no-cloud",
      plain));
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(fmt::format("train --model builtin:bolt --out {}", ppfm));
  ASSERT_EQ(r.status, 0) << r.err;
  copy_as_sensor_layout(dir / "plain", dir / "ind");

  r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {}", ppfm, plain,
                                    (dir / "plain.csv").string()));
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(fmt::format("detect --model {} --dataset {} --split val --sensor photoneo "
                                    "--out {}",
                                    ppfm, (dir / "ind").string(), (dir / "ind.csv").string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto want = bop::read_results_csv(dir / "plain.csv");
  const auto got = bop::read_results_csv(dir / "ind.csv");
  ASSERT_FALSE(want.empty());
  ASSERT_EQ(got.size(), 2 * want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    const auto& w = want[i % want.size()];
    EXPECT_EQ(got[i].scene_id, 5);
    EXPECT_EQ(got[i].im_id, i < want.size() ? 3 : 8);
    EXPECT_EQ(got[i].score, w.score) << i;
    EXPECT_TRUE(got[i].R.isApprox(w.R, 1e-6) && got[i].t.isApprox(w.t, 1e-6)) << i;
  }
  r = test::run_binpick(fmt::format("eval --dataset {} --split val --sensor photoneo --results {} "
                                    "--out {} --pictures 1",
                                    (dir / "ind").string(), (dir / "ind.csv").string(),
                                    (dir / "report").string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "report/report.json"));

  // Without the sensor: one message naming what is missing.
  r = test::run_binpick(fmt::format("detect --model {} --dataset {} --split val --out {}", ppfm,
                                    (dir / "ind").string(), (dir / "x.csv").string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("scene_camera.json"), std::string::npos) << r.err;
  r = test::run_binpick(fmt::format("detect --model {} --dataset {} --split val --sensor 'a/b' "
                                    "--out {}",
                                    ppfm, (dir / "ind").string(), (dir / "y.csv").string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--sensor 'a/b'"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

}  // namespace
