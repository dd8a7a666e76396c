// BOP's VSD recall on a synthetic bin: the ground truth as results scores 1 at every tau and
// threshold, the same poses pushed 0.6 diameters away from the camera about 0, and each
// estimate and each target is rendered once per image; without depth, triangles or a Vulkan
// device there is no VSD but the other scores are given.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/eval/metrics/bop_scores.hpp"
#include "tests/support/cli_run.hpp"

namespace binpick::eval {
namespace {

namespace fs = std::filesystem;

std::vector<bop::ResultRow> ground_truth_rows(const Dataset& dataset, double dz_mm) {
  std::vector<bop::ResultRow> rows;
  for (const auto& [key, image] : dataset.images)
    for (std::size_t i = 0; i < image.gt.size(); ++i) {
      bop::ResultRow r;
      r.scene_id = key.scene_id, r.im_id = key.im_id, r.obj_id = image.gt[i].obj_id;
      r.score = 1.0 - 0.001 * double(i);
      r.R = image.gt[i].model_to_camera.R;
      r.t = image.gt[i].model_to_camera.t + Eigen::Vector3d(0, 0, dz_mm);
      rows.push_back(r);
    }
  return rows;
}

TEST(BopVsdScores, GroundTruthScoresOneAndFarOffScoresAboutZero) {
  const fs::path dir = test::fresh_temp_dir("bop_vsd_scores");
  const std::string data = (dir / "data").string();
  const auto r = test::run_binpick(fmt::format(
      "synth --model builtin:shaft --out {} --bins 1 --objects 20 --width 640 --height 360 "
      "--noise 0.01",
      data));
  ASSERT_EQ(r.status, 0) << r.err;
  const Dataset dataset = load_dataset(data);

  const BopScores exact = bop_scores(dataset, ground_truth_rows(dataset, 0));
  ASSERT_TRUE(exact.has_vsd) << exact.vsd.unavailable;
  EXPECT_EQ(exact.vsd.average, 1.0);
  EXPECT_EQ(exact.average_recall, 1.0);
  ASSERT_EQ(exact.vsd.by_tau.size(), 10u);
  for (const auto& m : exact.vsd.by_tau)
    for (double recall : m.overall.recall) EXPECT_EQ(recall, 1.0);
  // One render per estimate and per target of the image; every pair is either compared or, its
  // sphere images apart, given 1 without rendering.
  EXPECT_EQ(exact.vsd.renders, exact.estimates + exact.targets);
  EXPECT_EQ(exact.vsd.pairs_compared + exact.vsd.pairs_skipped, exact.estimates * exact.targets);
  EXPECT_GT(exact.vsd.pairs_skipped, 0);

  const double diameter = dataset.models.at(1).diameter;
  const BopScores far = bop_scores(dataset, ground_truth_rows(dataset, 0.6 * diameter));
  ASSERT_TRUE(far.has_vsd);
  EXPECT_LT(far.vsd.average, 0.05);

  const BopScores skipped = bop_scores(dataset, ground_truth_rows(dataset, 0), {.vsd = false});
  EXPECT_FALSE(skipped.has_vsd);
  EXPECT_EQ(skipped.vsd.renders, 0);
  EXPECT_EQ(skipped.average_recall, 1.0);

  // An eval model without triangles (a point cloud) cannot be rendered: no VSD, the rest is.
  {
    const fs::path ply = fs::path(data) / "models_eval" / "obj_000001.ply";
    const fs::path kept = dir / "kept.ply";
    fs::rename(ply, kept);
    std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n0 0 0\n9 0 0\n0 9 0\n";
    const BopScores points = bop_scores(dataset, ground_truth_rows(dataset, 0));
    EXPECT_FALSE(points.has_vsd);
    EXPECT_NE(points.vsd.unavailable.find("no triangles"), std::string::npos)
        << points.vsd.unavailable;
    EXPECT_EQ(points.mssd.overall.average, 1.0);
    fs::rename(kept, ply);
  }

  // Without the depth images VSD cannot be computed; the other two still are.
  fs::remove_all(fs::path(data) / "test" / "000000" / "depth");
  const BopScores no_depth = bop_scores(load_dataset(data), ground_truth_rows(dataset, 0));
  EXPECT_FALSE(no_depth.has_vsd);
  EXPECT_NE(no_depth.vsd.unavailable.find("depth"), std::string::npos);
  EXPECT_EQ(no_depth.average_recall, 1.0);
  fs::remove_all(dir);
}

TEST(BopVsdScores, WithoutAVulkanDeviceEvalStillGivesTheOtherScores) {
  const fs::path dir = test::fresh_temp_dir("bop_vsd_no_device");
  const std::string data = (dir / "data").string(), csv = (dir / "gt.csv").string();
  auto r = test::run_binpick(fmt::format(
      "synth --model builtin:shaft --out {} --bins 1 --objects 5 --width 320 --height 180", data));
  ASSERT_EQ(r.status, 0) << r.err;
  const Dataset dataset = load_dataset(data);
  bop::write_results_csv(csv, ground_truth_rows(dataset, 0));
  ::setenv("BINPICK_VULKAN_DEVICE", "no-such-device", 1);
  r = test::run_binpick(fmt::format("eval --dataset {} --results {} --out {} --pictures 0 --json",
                                    data, csv, (dir / "report").string()));
  ::unsetenv("BINPICK_VULKAN_DEVICE");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto bop = nlohmann::json::parse(r.out)["datasets"][0]["bop"];
  EXPECT_TRUE(bop["ar_vsd"].is_null());
  EXPECT_NE(bop["vsd"]["unavailable"].get<std::string>().find("BINPICK_VULKAN_DEVICE"),
            std::string::npos);
  EXPECT_EQ(bop["ar"].get<double>(), 1.0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace binpick::eval
