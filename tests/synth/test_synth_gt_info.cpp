// scene_gt_info.json, mask/ and mask_visib/ of `binpick synth` follow bop_toolkit's
// calc_gt_info.py: recomputed here from the files as written (the depth PNG, the camera, the
// poses and the model, each part rendered alone where the toolkit's renderer puts pixel centres:
// bop_toolkit_sampling) they give the same numbers; and the dataset's
// test target lists count what scene_gt_info.json says.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include <nlohmann/json.hpp>

#include "host/core/mesh_normals.hpp"
#include "host/core/read_file.hpp"
#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "synth/bop_visibility.hpp"
#include "synth/render/bin_renderer.hpp"
#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

const fs::path& dataset() {
  static const fs::path dir = [] {
    const fs::path d = test::fresh_temp_dir("synth_gt_info");
    const auto run = test::run_binpick(fmt::format(
        "synth --model builtin:bracket --out '{}' --bins 2 --objects 24 --bin-size 300,200,150 "
        "--grid 4,2 --drop-height 250 --width 320 --height 180 --no-cloud --masks --noise 0.01 "
        "--cache-dir '{}'",
        (d / "out").string(), (d / "cache").string()));
    EXPECT_EQ(run.status, 0) << run.err;
    return d / "out";
  }();
  return dir;
}
struct RemoveAtExit : ::testing::Environment {
  void TearDown() override { fs::remove_all(dataset().parent_path()); }
};
const auto* const remove_at_exit = ::testing::AddGlobalTestEnvironment(new RemoveAtExit);

std::size_t lit(const GrayImage<std::uint8_t>& mask) {
  return std::size_t(std::count_if(mask.pixels.begin(), mask.pixels.end(), [](auto p) { return p > 0; }));
}

}  // namespace

TEST(SynthGtInfo, RecomputedFromTheWrittenFilesGivesTheSameNumbers) {
  const fs::path scene = dataset() / "test" / "000000";
  const bop::SceneCamera cam = bop::read_scene_cameras(scene / "scene_camera.json").at(0);
  const auto gt = bop::read_scene_gt(scene / "scene_gt.json").at(0);
  const auto info = bop::read_scene_gt_info(scene / "scene_gt_info.json").at(0);
  const GrayImage<std::uint16_t> depth = read_png16(scene / "depth" / "000000.png");
  Mesh model = load_model((dataset() / "models" / "obj_000001.ply").string(), {});
  if (model.normals.size() != model.positions.size()) compute_crease_normals(model);

  RenderCamera camera{depth.width, depth.height, cam.K(0, 0), cam.K(1, 1), cam.K(0, 2), cam.K(1, 2),
                      10.0, 10000.0};
  std::vector<Eigen::Isometry3d> poses;
  for (const auto& g : gt) poses.push_back(g.model_to_camera.isometry());
  const RenderedBin alone =
      BinRenderer(model, bop_toolkit_sampling(camera)).render(poses, {.silhouettes = true});

  ASSERT_EQ(info.size(), gt.size());
  int partly_hidden = 0;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    const bop::GroundTruthInfo& g = info[i];
    EXPECT_LE(g.px_count_valid, g.px_count_all) << i;
    EXPECT_LE(g.px_count_visib, g.px_count_all) << i;
    EXPECT_EQ(g.px_count_all, alone.px_all[i]) << i;
    const BopVisibility v = bop_visibility(alone.silhouettes[i],
                                           {depth.width, depth.height, &depth.pixels, cam.depth_scale},
                                           cam.K, kBopVisibDelta);
    EXPECT_EQ(g.px_count_valid, v.px_count_valid) << i;
    EXPECT_EQ(g.px_count_visib, v.px_count_visib) << i;
    EXPECT_EQ(g.bbox_visib, v.bbox_visib) << i;
    EXPECT_DOUBLE_EQ(g.visib_fract, g.px_count_all ? double(v.px_count_visib) / g.px_count_all : 0.0);
    const std::array<int, 4> none{-1, -1, -1, -1};
    EXPECT_EQ(g.bbox_obj, v.px_count_visib ? alone.bbox_all[i] : none) << i;
    const std::string name = fmt::format("000000_{:06d}.png", i);
    EXPECT_EQ(lit(read_png8(scene / "mask" / name)), g.px_count_all) << i;
    EXPECT_EQ(lit(read_png8(scene / "mask_visib" / name)), g.px_count_visib) << i;
    partly_hidden += g.visib_fract > 0.1 && g.visib_fract < 0.9;
  }
  EXPECT_GT(partly_hidden, 0);  // the bin has occlusion to judge
}

TEST(SynthGtInfo, TestTargetsCountTheInstancesAtLeastATenthVisible) {
  using json = nlohmann::json;
  const json bop19 = json::parse(read_file_bytes(dataset() / "test_targets_bop19.json"));
  const json bop24 = json::parse(read_file_bytes(dataset() / "test_targets_bop24.json"));
  EXPECT_EQ(bop24, json::parse(R"([{"im_id": 0, "scene_id": 0}, {"im_id": 0, "scene_id": 1}])"));
  json want = json::array();
  for (int scene = 0; scene < 2; ++scene) {
    const fs::path dir = dataset() / "test" / fmt::format("{:06d}", scene);
    const auto info = bop::read_scene_gt_info(dir / "scene_gt_info.json").at(0);
    const int n = int(std::count_if(info.begin(), info.end(), [](const auto& g) { return g.visib_fract >= 0.1; }));
    ASSERT_GT(n, 0);
    want.push_back({{"im_id", 0}, {"inst_count", n}, {"obj_id", 1}, {"scene_id", scene}});
  }
  EXPECT_EQ(bop19, want);
}

}  // namespace binpick

namespace binpick {

TEST(SynthGtInfo, ModelsEvalIsTheModelWithShortEdges) {
  const Mesh model = load_model((dataset() / "models" / "obj_000001.ply").string(), {});
  const Mesh eval = load_model((dataset() / "models_eval" / "obj_000001.ply").string(), {});
  const auto info = nlohmann::json::parse(read_file_bytes(dataset() / "models" / "models_info.json"));
  const auto eval_info = nlohmann::json::parse(read_file_bytes(dataset() / "models_eval" / "models_info.json"));
  const double diameter = info["1"]["diameter"].get<double>();
  EXPECT_NEAR(eval_info["1"]["diameter"].get<double>(), diameter, 1e-6 * diameter);
  EXPECT_GT(eval.positions.size(), model.positions.size());
  for (const auto& t : eval.triangles)
    for (int k = 0; k < 3; ++k)
      ASSERT_LE((eval.positions[t[k]] - eval.positions[t[(k + 1) % 3]]).norm(), 0.025 * diameter + 1e-4);
}

}  // namespace binpick
