// End to end detection: a built-in part placed at a known pose above a floor, rendered into a
// depth image (a point splat z-buffer), must be found within 5 % of the diameter and 5 degrees
// (symmetric poses count as equal), through the depth path and the point cloud path; and on
// bins made by `binpick synth` of every built-in part, the top-voted hypothesis of most bins is a
// real part's pose.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/detect/detector.hpp"
#include "host/eval/metrics/pose_error.hpp"
#include "host/app/options/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/surface_sampling.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;

namespace {

struct PoseError {
  double t = 1e9, deg = 1e9;
};

// The error of an estimated model-to-camera pose against a true one, the smallest over the
// part's symmetries (eval's definition: rotation error = angle of R_gt^T R_est, in degrees).
PoseError pose_error(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const Eigen::Matrix3d& Rg,
                     const Eigen::Vector3d& tg, const PartSymmetries& sym) {
  const eval::PoseError e = eval::symmetric_pose_error(Rg, tg, R, t, sym);
  return {e.translation_mm, e.rotation_deg};
}

struct Scene {
  DepthImage depth;
  bp_camera cam{};
  PointCloud cloud;  // the visible samples, camera frame (for the cloud path)
};

// The part's surface samples moved by T, z-buffered into a w x h image (f px) over a floor at
// floor_z: every pixel keeps the nearest sample, which is also the visible cloud.
Scene render(const Mesh& mesh, const Eigen::Isometry3f& T, float floor_z) {
  Scene s;
  const std::uint32_t w = 320, h = 240;
  s.cam = {600.0f, 600.0f, (w - 1) / 2.0f, (h - 1) / 2.0f, 0.1f, w, h, 0};
  const PointCloud samples = sample_surface(mesh, 400000);
  std::vector<float> z(w * h, floor_z);
  std::vector<int> owner(w * h, -1);
  for (std::size_t i = 0; i < samples.points.size(); ++i) {
    const Eigen::Vector3f p = T * samples.points[i];
    const long u = std::lround(s.cam.fx * p.x() / p.z() + s.cam.cx);
    const long v = std::lround(s.cam.fy * p.y() / p.z() + s.cam.cy);
    if (u < 0 || v < 0 || u >= long(w) || v >= long(h)) continue;
    if (p.z() < z[v * w + u]) z[v * w + u] = p.z(), owner[v * w + u] = int(i);
  }
  s.depth = {w, h, std::vector<std::uint16_t>(w * h)};
  for (std::size_t k = 0; k < z.size(); ++k) {
    s.depth.raw[k] = std::uint16_t(std::lround(z[k] / s.cam.depth_scale));
    if (owner[k] < 0) continue;
    s.cloud.points.push_back(T * samples.points[owner[k]]);
    s.cloud.normals.push_back(T.linear() * samples.normals[owner[k]]);
  }
  return s;
}

class DetectKnownPose : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(DetectKnownPose, FoundWithinFivePercentAndFiveDegrees) {
  const Model part = cli::load_part({"builtin:" + GetParam(), {}});
  const PpfModel model = train_ppf_model(part.mesh, {});
  Detector detector(model, {});
  for (int trial = 0; trial < 2; ++trial) {
    Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
    T.linear() = Eigen::AngleAxisf(0.7f + 1.9f * trial, Eigen::Vector3f(0.4f, -0.7f + trial, 0.6f).normalized())
                     .toRotationMatrix();
    T.translation() = Eigen::Vector3f(12.0f - 20.0f * trial, -8.0f, 600.0f);
    const Scene scene = render(part.mesh, T, 600.0f + model.diameter);
    for (int path = 0; path < 2; ++path) {
      DetectTimes times;
      const auto found = path == 0 ? detector.detect(scene.depth, scene.cam, &times)
                                   : detector.detect(scene.cloud, &times);
      ASSERT_FALSE(found.empty());
      const PoseError e = pose_error(found[0].R, found[0].t, T.linear().cast<double>(),
                                     T.translation().cast<double>(), part.symmetries);
      EXPECT_LT(e.t, 0.05 * model.diameter) << GetParam() << " trial " << trial << " path " << path;
      EXPECT_LT(e.deg, 5.0) << GetParam() << " trial " << trial << " path " << path;
      EXPECT_GT(found[0].votes, 0u);
      EXPECT_GT(times.vote_ms, 0.0);
    }
  }
}

// Not the plate yet: a flat sheet fits any plane (the floor) as well as itself, and upside down
// as well as the right way up, wherever its holes do not tell; verification does not yet look
// for the free space a part's holes and outline predict.
INSTANTIATE_TEST_SUITE_P(BuiltinParts, DetectKnownPose,
                         ::testing::Values("bracket", "bolt", "tee", "shaft"));

// Bins of a built-in part made, trained on and detected in through the command line, as a user
// runs it, into dir: the results rows.
static void synth_train_detect(const std::string& name, const std::filesystem::path& dir,
                        const std::string& synth_options, std::vector<bop::ResultRow>& rows) {
  const std::string data = (dir / "data").string(), ppfm = (dir / "part.ppfm").string();
  const std::string csv = (dir / "results.csv").string();
  auto r = test::run_binpick(
      fmt::format("synth --model builtin:{} --out {} {}", name, data, synth_options));
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(fmt::format("train --model builtin:{} --out {}", name, ppfm));
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {}", ppfm, data, csv));
  ASSERT_EQ(r.status, 0) << r.err;
  rows = bop::read_results_csv(csv);
}

// Synthetic bins through the command line, as a user runs it.
TEST(DetectSynthBins, TopVotedHypothesisIsRightInMostBins) {
  int right = 0, bins = 0;
  std::string report;
  for (const std::string name : {"bracket", "bolt", "tee"}) {
    const auto dir = test::fresh_temp_dir("detect_bins_" + name);
    std::vector<bop::ResultRow> rows;
    ASSERT_NO_FATAL_FAILURE(synth_train_detect(name, dir, "--bins 2 --objects 35", rows));
    const Model part = cli::load_part({"builtin:" + name, {}});
    for (int scene = 0; scene < 2; ++scene) {
      ++bins;
      const auto gt = bop::read_scene_gt(dir / "data" / "test" / fmt::format("{:06d}", scene) / "scene_gt.json");
      const bop::ResultRow* top = nullptr;
      for (const auto& row : rows)
        if (row.scene_id == scene && (!top || row.score > top->score)) top = &row;
      if (!top) continue;
      PoseError best;
      for (const auto& g : gt.at(0)) {
        const PoseError e = pose_error(top->R, top->t, g.model_to_camera.R, g.model_to_camera.t,
                                       part.symmetries);
        if (e.t < best.t) best = e;
      }
      // "right": within 10 % of the diameter (52 mm) and 10 degrees of a part
      const bool ok = best.t < 5.2 && best.deg < 10.0;
      right += ok;
      report += fmt::format("{} bin {}: {:.2f} mm {:.2f} deg {}\n", name, scene, best.t, best.deg,
                            ok ? "right" : "wrong");
    }
    std::filesystem::remove_all(dir);
  }
  std::cout << report;
  EXPECT_GE(right * 3, bins * 2) << report;  // at least two thirds of the bins
}

// Noisy bins of every built-in part through the command line: a fixed seed, so the counts are
// deterministic and the floors, set just under what was measured when they were written, catch a
// drop at once. "Right" as in the report's loose operating point: within 10 % of the diameter
// and 15 degrees of a part (symmetric poses equal).
// Bins as synth makes them by default: the bin in view (its floor mostly bare with 35 parts),
// found and kept out by `--bin auto`.
TEST(DetectSynthBins, NoisyBinsOfEveryPartKeepTheirPrecision) {
  int top_right = 0, images = 0, all_right = 0, hypotheses = 0;
  std::string report;
  for (const std::string& name : builtin_part_names()) {
    const auto dir = test::fresh_temp_dir("detect_noisy_" + name);
    std::vector<bop::ResultRow> rows;
    ASSERT_NO_FATAL_FAILURE(
        synth_train_detect(name, dir, "--bins 3 --objects 35 --noise 0.02 --seed 5", rows));
    const Model part = cli::load_part({"builtin:" + name, {}});
    const double d = builtin_part_nominal_diameter(name);
    int part_top = 0, part_all = 0;
    for (int scene = 0; scene < 3; ++scene) {
      const auto gt = bop::read_scene_gt(dir / "data" / "test" / fmt::format("{:06d}", scene) / "scene_gt.json");
      bool first = true;
      for (const auto& row : rows) {
        if (row.scene_id != scene) continue;
        PoseError best;
        for (const auto& g : gt.at(0)) {
          const PoseError e = pose_error(row.R, row.t, g.model_to_camera.R, g.model_to_camera.t,
                                         part.symmetries);
          if (e.t < best.t) best = e;
        }
        const bool ok = best.t < 0.1 * d && best.deg < 15.0;
        part_all += ok;
        ++hypotheses;
        if (first) part_top += ok, ++images;
        first = false;
      }
    }
    top_right += part_top;
    all_right += part_all;
    report += fmt::format("{}: top-ranked right in {} of 3 bins, {} hypotheses right\n", name,
                          part_top, part_all);
    std::filesystem::remove_all(dir);
  }
  std::cout << report;
  EXPECT_EQ(images, 15) << report;
  // Measured with the bin in view: bracket 3/3 top, 14/15 all; bolt 3, 15; tee 3, 12; shaft 3,
  // 15; plate 0, 0 (a flat sheet fits any plane, and upside down: see DetectKnownPose). Without
  // keeping the floor out of the crops, the shaft fell to 0 and 0 (sunk into the floor).
  // The counts follow the piles of this one seed as well as the detector: when the drop's rest
  // test went by poses, the freezer woke touching parts and erp2 followed the step
  // (docs/synthesis.md), these bins changed and bolt went 14 -> 15, tee 13 -> 12, plate 1 -> 0
  // (57 -> 56), while over more seeds the old and the new piles did alike: tee 171 and 171 of
  // 180 hypotheses right (seeds 5 to 16), bracket 89 and 88, bolt 89 and 89 of 90 (5 to 10),
  // plate 2 and 2 of 60 (5 to 8).
  EXPECT_GE(top_right, 12) << report;
  EXPECT_GE(all_right, 56) << report;
}
