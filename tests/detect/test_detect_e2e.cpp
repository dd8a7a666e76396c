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
#include "host/app/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/surface_sampling.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;

namespace {

struct PoseError {
  double t = 1e9, deg = 1e9;
};

// The error of an estimated model-to-camera pose against a true one, the smallest over the
// part's discrete symmetries (rotation error = angle of R_gt^T R_est, in degrees).
PoseError pose_error(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const Eigen::Matrix3d& Rg,
                     const Eigen::Vector3d& tg, const PartSymmetries& sym) {
  std::vector<Eigen::Matrix4d> all = sym.discrete;
  all.push_back(Eigen::Matrix4d::Identity());
  PoseError best;
  for (const Eigen::Matrix4d& S : all) {
    const Eigen::Matrix3d Rs = Rg * S.block<3, 3>(0, 0);
    const Eigen::Vector3d ts = Rg * S.block<3, 1>(0, 3) + tg;
    const double c = std::clamp(((Rs.transpose() * R).trace() - 1) / 2, -1.0, 1.0);
    const double deg = std::acos(c) * 180 / std::numbers::pi;
    if (deg < best.deg) best = {(t - ts).norm(), deg};
  }
  return best;
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

INSTANTIATE_TEST_SUITE_P(BuiltinParts, DetectKnownPose, ::testing::Values("bracket", "bolt", "tee"));

// Synthetic bins through the command line, as a user runs it.
TEST(DetectSynthBins, TopVotedHypothesisIsRightInMostBins) {
  int right = 0, bins = 0;
  std::string report;
  for (const std::string name : {"bracket", "bolt", "tee"}) {
    const auto dir = test::fresh_temp_dir("detect_bins_" + name);
    const std::string data = (dir / "data").string(), ppfm = (dir / "part.ppfm").string();
    const std::string csv = (dir / "results.csv").string();
    auto r = test::run_binpick(fmt::format("synth --model builtin:{} --out {} --bins 2 --objects 35", name, data));
    ASSERT_EQ(r.status, 0) << r.err;
    r = test::run_binpick(fmt::format("train --model builtin:{} --out {}", name, ppfm));
    ASSERT_EQ(r.status, 0) << r.err;
    r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {}", ppfm, data, csv));
    ASSERT_EQ(r.status, 0) << r.err;
    const Model part = cli::load_part({"builtin:" + name, {}});
    const auto rows = bop::read_results_csv(csv);
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
