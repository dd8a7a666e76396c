// `binpick detect` and `binpick eval` on a dataset in the layout of BOP's industrial datasets:
// another split, every file with the sensor's suffix, several images per scene with ids other
// than 0. The results must be those of the plain layout, row for row. Then the same layout with
// two objects (issue 15's round trip): detected with both models at once, evaluated per obj_id.
#include <gtest/gtest.h>

#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

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

// The rows of `rows` of one image and obj_id, in file order.
std::vector<bop::ResultRow> rows_of(const std::vector<bop::ResultRow>& rows, int im_id, int obj_id) {
  std::vector<bop::ResultRow> out;
  for (const auto& r : rows)
    if (r.im_id == im_id && r.obj_id == obj_id) out.push_back(r);
  return out;
}

TEST(DetectSensorLayout, TwoObjectsDetectedTogetherAndEvaluatedPerObjId) {
  const fs::path dir = test::fresh_temp_dir("detect_two_objects");
  const std::string plain = (dir / "plain").string(), ind = (dir / "ind").string();
  auto r = test::run_binpick(fmt::format(
      "synth --model builtin:bracket --distractors builtin:tee:0.5 --out {} --bins 1 --objects 20 "
      "--width 480 --height 270 --no-cloud",
      plain));
  ASSERT_EQ(r.status, 0) << r.err;
  // Trained models under their BOP names, and the same bytes under names that say nothing.
  fs::create_directories(dir / "models");
  const fs::path bracket = dir / "models/obj_000001.ppfm", tee = dir / "models/obj_000002.ppfm";
  for (const auto& [part, file] : {std::pair{"bracket", bracket}, std::pair{"tee", tee}}) {
    r = test::run_binpick(fmt::format("train --model builtin:{} --out {}", part, file.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    fs::copy_file(file, dir / (std::string(part) + ".ppfm"));
  }
  copy_as_sensor_layout(dir / "plain", dir / "ind");
  const std::string layout = fmt::format("--dataset {} --split val --sensor photoneo", ind);
  // Ten highest points, so that each object's are not all on the other's parts.
  const std::string detect_layout = layout + " --hypotheses 10";

  // Each model alone, then both from the directory, then both as files with --obj-id.
  for (const auto& [model, out] : {std::pair{bracket, "one.csv"}, std::pair{tee, "two.csv"},
                                   std::pair{dir / "models", "both.csv"}}) {
    r = test::run_binpick(fmt::format("detect --model {} {} --out {}", model.string(),
                                      detect_layout, (dir / out).string()));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  r = test::run_binpick(fmt::format(
      "detect --model {} --obj-id 2 --model {} --obj-id 1 {} --out {} --verbose",
      (dir / "tee.ppfm").string(), (dir / "bracket.ppfm").string(), detect_layout,
      (dir / "named.csv").string()));
  ASSERT_EQ(r.status, 0) << r.err;
  // The image is prepared once: the second model's stages start after the upload and points.
  // (The low-pass is each model's: its region's, from the points its mask keeps.)
  const std::size_t second = r.out.find("scene 5 image 3 obj_id 2: ");
  ASSERT_NE(second, std::string::npos) << r.out;
  const std::string stages = r.out.substr(second, r.out.find('\n', second) - second);
  EXPECT_EQ(stages.find(" upload "), std::string::npos) << stages;
  EXPECT_EQ(stages.find(" points "), std::string::npos) << stages;
  EXPECT_NE(r.out.find("scene 5 image 3 obj_id 1: 10 hypotheses; upload "), std::string::npos);
  EXPECT_EQ(test::without_time(test::slurp(dir / "named.csv")),
            test::without_time(test::slurp(dir / "both.csv")));

  // Per image: the bracket's rows as it finds them alone, then the tee's (BOP's order), one time.
  const auto one = bop::read_results_csv(dir / "one.csv"), two = bop::read_results_csv(dir / "two.csv");
  const auto both = bop::read_results_csv(dir / "both.csv");
  ASSERT_EQ(both.size(), one.size() + two.size());
  std::size_t at = 0;
  for (int im_id : {3, 8}) {
    const auto first = rows_of(one, im_id, 1), second = rows_of(two, im_id, 2);
    ASSERT_FALSE(first.empty());
    ASSERT_FALSE(second.empty());
    const double image_time = both[at].time;
    for (const auto* part : {&first, &second})
      for (const auto& want : *part) {
        const auto& got = both[at++];
        EXPECT_EQ(got.im_id, im_id);
        EXPECT_EQ(got.obj_id, want.obj_id);
        EXPECT_EQ(got.score, want.score);
        EXPECT_TRUE(got.R.isApprox(want.R, 1e-9) && got.t.isApprox(want.t, 1e-9));
        EXPECT_EQ(got.time, image_time);
      }
  }
  // The details name the obj_id of every row.
  const std::string details = test::slurp(dir / "both.details.csv");
  EXPECT_EQ(details.rfind("scene_id,im_id,obj_id,rank,", 0), 0u) << details.substr(0, 80);
  EXPECT_NE(details.find("\n5,8,2,0,"), std::string::npos);

  // eval: the paper's figures per obj_id next to those of all rows; BOP's per obj_id.
  r = test::run_binpick(fmt::format("eval {} --results {} --out {} --pictures 0 --json", layout,
                                    (dir / "both.csv").string(), (dir / "report").string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto d = nlohmann::json::parse(r.out)["datasets"][0];
  ASSERT_EQ(d["objects"].size(), 2u) << d.dump(1);
  for (int k = 0; k < 2; ++k) {
    const auto& o = d["objects"][k];
    EXPECT_EQ(o["obj_id"].get<int>(), k + 1);
    EXPECT_EQ(o["images"].get<int>(), 2);
    EXPECT_EQ(o["hypotheses"].get<std::size_t>(), (k == 0 ? one : two).size());
    EXPECT_GT(o["precision"]["loose"]["top"].get<double>(), 0.0) << o.dump(1);
    EXPECT_EQ(d["bop"]["objects"][k]["obj_id"].get<int>(), k + 1);
  }
  EXPECT_EQ(d["hypotheses"].get<std::size_t>(), both.size());
  r = test::run_binpick(fmt::format("eval {} --results {} --out {} --pictures 0", layout,
                                    (dir / "both.csv").string(), (dir / "report").string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\n  obj_id 1 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  obj_id 2 "), std::string::npos) << r.out;
  // report.html: a summary row per obj_id under the dataset's.
  const std::string html = test::slurp(dir / "report" / "report.html");
  EXPECT_NE(html.find("<tr><td>&nbsp;&nbsp;obj_id 1</td>"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>&nbsp;&nbsp;obj_id 2</td>"), std::string::npos);

  // The dataset's BOP models/ folder: its meshes are trained when detect starts.
  r = test::run_binpick(fmt::format("detect --model {}/models {} --out {}", ind, layout,
                                    (dir / "meshes.csv").string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("obj_000002.ply (obj_id 2) in "), std::string::npos) << r.out;
  const auto meshes = bop::read_results_csv(dir / "meshes.csv");
  EXPECT_FALSE(rows_of(meshes, 8, 1).empty());
  EXPECT_FALSE(rows_of(meshes, 8, 2).empty());

  // Refused with one message: two models of one obj_id, a directory without models, an
  // obj_id the dataset's models_info.json lacks.
  r = test::run_binpick(fmt::format("detect --model {} --model {} --obj-id 1 --obj-id 1 {} --out {}",
                                    (dir / "tee.ppfm").string(), (dir / "bracket.ppfm").string(),
                                    layout, (dir / "x.csv").string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("two models have obj_id 1"), std::string::npos) << r.err;
  fs::create_directories(dir / "empty");
  r = test::run_binpick(fmt::format("detect --model {} {} --out {}", (dir / "empty").string(),
                                    layout, (dir / "x.csv").string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("holds no model"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.csv"));
  r = test::run_binpick(fmt::format("detect --model {} --obj-id 3 {} --out {}",
                                    (dir / "tee.ppfm").string(), layout, (dir / "three.csv").string()));
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(fmt::format("eval {} --results {} --out {} --pictures 0", layout,
                                    (dir / "three.csv").string(), (dir / "report3").string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("has obj_id 3, which"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("models_info.json lacks"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

}  // namespace
