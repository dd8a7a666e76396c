// `binpick synth` scenes beyond the paper's, as a user runs it and reads the dataset back with
// the project's BOP readers: distractors (their own obj_ids, models, masks, in one instance order
// across the files, deterministic by seed), a tilted camera whose ground truth projects parts
// where they render, and a bin from a mesh file, rendered or not.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/models_info.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/formats/mesh/mesh_writers.hpp"
#include "host/train/surface_sampling.hpp"
#include "synth/bin/bin_model.hpp"
#include "tests/support/cli_run.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

// One temporary directory (and decomposition cache) for every run of this file.
const fs::path& root() {
  static const fs::path dir = test::fresh_temp_dir("synth_scene");
  return dir;
}
struct RemoveRootAtExit : ::testing::Environment {
  void TearDown() override { fs::remove_all(root()); }
};
const auto* const remove_root = ::testing::AddGlobalTestEnvironment(new RemoveRootAtExit);

// Small bins: 16 parts in a half-size bin, a tiny image.
test::CliRun synth(const std::string& out, const std::string& extra) {
  return test::run_binpick(fmt::format(
      "synth --model builtin:bracket --out '{}' --bins 1 --objects 16 --bin-size 300,200,150 "
      "--grid 4,2 --drop-height 250 --width 240 --height 135 --no-cloud --masks --cache-dir '{}' "
      "{}",
      (root() / out).string(), (root() / "cache").string(), extra));
}

fs::path scene_dir(const std::string& out) { return root() / out / "test" / "000000"; }

struct Scene {
  bop::SceneCamera camera;
  std::vector<bop::GroundTruth> gt;
  std::vector<bop::GroundTruthInfo> info;
  std::vector<GrayImage<std::uint8_t>> masks;
  GrayImage<std::uint16_t> depth;
};

Scene read_scene(const std::string& out) {
  const fs::path dir = scene_dir(out);
  Scene s;
  s.camera = bop::read_scene_cameras(dir / "scene_camera.json").at(0);
  s.gt = bop::read_scene_gt(dir / "scene_gt.json").at(0);
  s.info = bop::read_scene_gt_info(dir / "scene_gt_info.json").at(0);
  for (std::size_t i = 0; i < s.gt.size(); ++i)
    s.masks.push_back(read_png8(dir / "mask_visib" / fmt::format("000000_{:06d}.png", i)));
  s.depth = read_png16(dir / "depth" / "000000.png");
  return s;
}

Mesh model_of(const std::string& out, int obj_id) {
  return load_model((root() / out / "models" / fmt::format("obj_{:06d}.ply", obj_id)).string(), {});
}

// The share of the model's surface samples, posed, that project onto (or next to) the mask.
double share_on_mask(const PointCloud& samples, const bop::Pose& pose, const Eigen::Matrix3d& K,
                     const GrayImage<std::uint8_t>& mask) {
  int on = 0;
  for (const auto& p : samples.points) {
    const Eigen::Vector3d c = pose.R * p.cast<double>() + pose.t;
    const long u = std::lround(K(0, 0) * c.x() / c.z() + K(0, 2));
    const long v = std::lround(K(1, 1) * c.y() / c.z() + K(1, 2));
    bool hit = false;
    for (long dv = -1; dv <= 1 && !hit; ++dv)
      for (long du = -1; du <= 1 && !hit; ++du) {
        const long x = u + du, y = v + dv;
        hit = x >= 0 && y >= 0 && x < long(mask.width) && y < long(mask.height) &&
              mask.pixels[std::size_t(y) * mask.width + std::size_t(x)] > 0;
      }
    on += hit;
  }
  return double(on) / double(samples.points.size());
}

std::size_t mask_pixels(const GrayImage<std::uint8_t>& mask) {
  return std::size_t(
      std::count_if(mask.pixels.begin(), mask.pixels.end(), [](auto p) { return p > 0; }));
}

const char* kDistractors = "--distractors builtin:bolt:0.25,builtin:tee --seed 3";

// The distractors' ground truth round-trips: obj_ids in their shares, models and models_info
// entries with diameters and the built-in parts' symmetries, and each instance's mask, info and
// pose agreeing with one another (one instance order across the files).
TEST(SynthScene, DistractorGroundTruthRoundTrips) {
  const auto run = synth("mixed", kDistractors);
  ASSERT_EQ(run.status, 0) << run.err;
  const Scene s = read_scene("mixed");
  std::map<int, int> per_obj;
  for (const auto& g : s.gt) ++per_obj[g.obj_id];
  ASSERT_EQ(s.gt.size(), 16u) << run.out;  // none left the bin
  EXPECT_EQ(per_obj[2], 4);                // 0.25 of 16
  EXPECT_EQ(per_obj[3], 2);   // the default 0.25 split over two distractors: 0.125 of 16
  EXPECT_EQ(per_obj[1], 10);  // the rest
  // Mixed in the waves, not appended: some distractor comes before the last bracket.
  std::size_t first_distractor = s.gt.size(), last_bracket = 0;
  for (std::size_t i = 0; i < s.gt.size(); ++i) {
    if (s.gt[i].obj_id != 1)
      first_distractor = std::min(first_distractor, i);
    else
      last_bracket = i;
  }
  EXPECT_LT(first_distractor, last_bracket);

  const bop::ModelsInfo info =
      bop::read_models_info(root() / "mixed" / "models" / "models_info.json");
  ASSERT_EQ(info.size(), 3u);
  EXPECT_EQ(info.at(2).symmetries.discrete.size(), 5u);  // the bolt's hexagonal head
  EXPECT_EQ(info.at(3).symmetries.discrete.size(), 1u);  // the tee's half turn
  std::map<int, PointCloud> samples;
  for (int id = 1; id <= 3; ++id) {
    const Mesh model = model_of("mixed", id);
    EXPECT_NEAR(info.at(id).diameter, 52.0, 0.5) << id;
    samples[id] = sample_surface(model, 1500);
  }

  ASSERT_EQ(s.info.size(), s.gt.size());
  int checked = 0;
  for (std::size_t i = 0; i < s.gt.size(); ++i) {
    EXPECT_EQ(mask_pixels(s.masks[i]), s.info[i].px_count_visib) << i;
    if (s.info[i].visib_fract < 0.9) continue;
    // An unoccluded instance's model, posed, covers its mask: the right model and pose for it.
    const double own =
        share_on_mask(samples[s.gt[i].obj_id], s.gt[i].model_to_camera, s.camera.K, s.masks[i]);
    EXPECT_GT(own, 0.95) << "instance " << i << " obj " << s.gt[i].obj_id;
    checked += s.gt[i].obj_id != 1;
  }
  EXPECT_GT(checked, 0);  // some distractor was checked
}

// Same seed, same bytes, distractors included; another seed, another bin.
TEST(SynthScene, DistractorsAreDeterministic) {
  ASSERT_EQ(synth("same_a", kDistractors).status, 0);
  ASSERT_EQ(synth("same_b", kDistractors).status, 0);
  ASSERT_EQ(synth("other", "--distractors builtin:bolt:0.25,builtin:tee --seed 4").status, 0);
  for (const std::string file : {"scene_gt.json", "scene_gt_info.json", "depth/000000.png",
                                 "gray/000000.png", "mask_visib/000000_000003.png"}) {
    const std::string a = test::slurp(scene_dir("same_a") / file);
    ASSERT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, test::slurp(scene_dir("same_b") / file)) << file;
  }
  EXPECT_NE(test::slurp(scene_dir("same_a") / "scene_gt.json"),
            test::slurp(scene_dir("other") / "scene_gt.json"));
  EXPECT_EQ(test::slurp(root() / "same_a" / "models" / "models_info.json"),
            test::slurp(root() / "same_b" / "models" / "models_info.json"));
}

// A tilted camera: scene_camera.json's world-to-camera has the tilt, every part's ground truth
// put back in the world lies in the bin, and each well visible part's model projects onto its
// rendered mask.
TEST(SynthScene, TiltedCameraGroundTruthProjectsWherePartsRender) {
  const double tilt = 30.0;
  const auto run =
      synth("tilted", fmt::format("--camera-tilt {} --intrinsics 150,150,119.5,67.5", tilt));
  ASSERT_EQ(run.status, 0) << run.err;
  const Scene s = read_scene("tilted");
  const Eigen::Isometry3d w2c = s.camera.world_to_camera.isometry();
  const double t = tilt * M_PI / 180;
  // The optical axis, in the world, points from -y down to the floor centre.
  EXPECT_TRUE((w2c.linear().transpose() * Eigen::Vector3d::UnitZ())
                  .isApprox(Eigen::Vector3d(0, std::sin(t), -std::cos(t)), 1e-9));
  EXPECT_TRUE(w2c.inverse().translation().isApprox(
      Eigen::Vector3d(0, -1000 * std::sin(t), 1000 * std::cos(t)), 1e-6));
  EXPECT_EQ(s.camera.K(0, 0), 150.0);

  const PointCloud samples = sample_surface(model_of("tilted", 1), 1500);
  int checked = 0;
  for (std::size_t i = 0; i < s.gt.size(); ++i) {
    const Eigen::Isometry3d m2w = w2c.inverse() * s.gt[i].model_to_camera.isometry();
    const Eigen::Vector3d centre = m2w.translation();
    EXPECT_LE(std::abs(centre.x()), 150.0) << i;
    EXPECT_LE(std::abs(centre.y()), 100.0) << i;
    EXPECT_GE(centre.z(), 0.0) << i;
    if (s.info[i].visib_fract < 0.9) continue;
    EXPECT_GT(share_on_mask(samples, s.gt[i].model_to_camera, s.camera.K, s.masks[i]), 0.95) << i;
    // Teeth: the pose the untilted camera would give puts the model elsewhere.
    bop::Pose untilted = bop::Pose::from(s.gt[i].model_to_camera.isometry());
    untilted.t = Eigen::AngleAxisd(t, Eigen::Vector3d::UnitX()) * untilted.t;
    EXPECT_LT(share_on_mask(samples, untilted, s.camera.K, s.masks[i]), 0.5) << i;
    ++checked;
  }
  EXPECT_GE(checked, 3);
}

// A bin from a mesh file (the built-in bin's own mesh, here a static triangle mesh): parts land
// in it, the camera sees its floor at 1000 mm; with --bin-render none the floor is not seen.
TEST(SynthScene, BinMeshIsCollidedWithAndRenderedOrNot) {
  const fs::path mesh = root() / "bin.ply";
  write_ply(mesh, built_in_bin({300, 200, 150}, {10, 25}).mesh);
  const auto floor_pixels = [](const Scene& s) {
    std::size_t n = 0;
    for (const auto d : s.depth.pixels) n += std::abs(d * s.camera.depth_scale - 1000.0) < 0.3;
    return n;
  };
  for (const std::string render : {"full", "none"}) {
    const std::string out = "mesh_" + render;
    const auto run =
        synth(out, fmt::format("--bin-mesh '{}' --bin-render {}", mesh.string(), render));
    ASSERT_EQ(run.status, 0) << run.err;
    const Scene s = read_scene(out);
    EXPECT_EQ(s.gt.size(), 16u) << run.out;
    const Eigen::Isometry3d c2w = s.camera.world_to_camera.isometry().inverse();
    for (const auto& g : s.gt) {
      const Eigen::Vector3d centre = c2w * g.model_to_camera.t;
      EXPECT_LE(std::abs(centre.x()), 150.0);
      EXPECT_LE(std::abs(centre.y()), 100.0);
      EXPECT_GE(centre.z(), 0.0);
    }
    const std::size_t pixels = std::size_t(s.depth.width) * s.depth.height;
    if (render == "full")
      EXPECT_GT(floor_pixels(s), pixels / 5);
    else
      EXPECT_LT(floor_pixels(s), pixels / 100);
  }
}

}  // namespace
}  // namespace binpick
