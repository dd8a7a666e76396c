// BOP's VSD on Vulkan renderings of a box: zero at the ground truth, one far off, one renderer
// per camera; and (with python3 and numpy) binpick's errors on random images and on renderings
// against a transcription of the toolkit's pose_error.vsd, visibility.py and
// misc.depth_im_to_dist_im_fast (tools/bop_toolkit_check.py --vsd-cases), within 1e-6.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/core/mesh_normals.hpp"
#include "host/eval/metrics/bop_vsd.hpp"
#include "host/eval/metrics/vsd_rendering.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick::eval {
namespace {

// The model (a 50 mm box, centred) at 800 mm, slightly turned, rendered with Vulkan.
struct RenderedBox {
  Mesh mesh = test::box({50, 50, 50});
  Eigen::Matrix3d K;
  RigidPose gt;
  std::uint32_t width = 160, height = 120;
  RenderedBox() {
    for (auto& p : mesh.positions) p -= Eigen::Vector3f(25, 25, 25);
    compute_crease_normals(mesh);
    K << 300, 0, 79.5, 0, 300, 59.5, 0, 0, 1;
    gt.R = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();
    gt.t = {5, -3, 800};
  }
  double diameter() const { return 50 * std::sqrt(3.0); }
};

TEST(BopVsdRendered, PoseOfTheGroundTruthIsZeroAndOneFarOffIsOne) {
  RenderedBox box;
  ModelDepthRenderer renderer({{1, box.mesh}});
  // The test image: the ground truth's own rendering, in 0.1 mm steps.
  const auto gt = renderer.render(box.K, box.width, box.height, {{1, box.gt}});
  ASSERT_EQ(gt.size(), 1u);
  ASSERT_GT(gt[0].pixels.size(), 500u);
  std::vector<std::uint16_t> raw(std::size_t(box.width) * box.height, 0);
  for (std::size_t i = 0; i < gt[0].pixels.size(); ++i)
    raw[gt[0].pixels[i]] = std::uint16_t(std::lround(gt[0].depth_mm[i] * 10));
  const BopDepthImage test{box.width, box.height, &raw, 0.1};
  VsdSettings s;
  s.diameter = box.diameter();
  for (double e : vsd_errors(gt[0], gt[0], test, box.K, s)) EXPECT_EQ(e, 0.0);

  // Re-rendered at the same pose: the same pixels and depths, so error 0 again.
  const auto again = renderer.render(box.K, box.width, box.height, {{1, box.gt}, {1, box.gt}});
  ASSERT_EQ(again.size(), 2u);
  for (double e : vsd_errors(again[1], gt[0], test, box.K, s)) EXPECT_EQ(e, 0.0);

  // 0.6 diameters nearer the camera: every pixel of the estimate is visible and at least that
  // far from the ground truth's surface, beyond the largest tau (0.5): error 1 at every tau.
  // 0.6 diameters farther away: hidden behind the test surface except where the ground truth
  // is seen, and misaligned there: 1 again.
  for (double dz : {-0.6, 0.6}) {
    RigidPose off = box.gt;
    off.t.z() += dz * box.diameter();
    const auto est = renderer.render(box.K, box.width, box.height, {{1, off}});
    for (double e : vsd_errors(est[0], gt[0], test, box.K, s)) EXPECT_EQ(e, 1.0) << dz;
  }

  // A small shift sideways: between 0 and 1, not increasing with tau.
  RigidPose near = box.gt;
  near.t.x() += 4;
  const auto est = renderer.render(box.K, box.width, box.height, {{1, near}});
  const auto e = vsd_errors(est[0], gt[0], test, box.K, s);
  EXPECT_GT(e.front(), 0.0);
  EXPECT_LT(e.back(), 1.0);
  for (std::size_t k = 1; k < e.size(); ++k) EXPECT_LE(e[k], e[k - 1]);
}

TEST(BopVsdRendered, EachImageIsDrawnWithItsOwnCamera) {
  RenderedBox box;
  ModelDepthRenderer renderer({{1, box.mesh}});
  const auto first = renderer.render(box.K, box.width, box.height, {{1, box.gt}});
  Eigen::Matrix3d wider = box.K;
  wider(0, 0) = wider(1, 1) = 450;  // 1.5 times the focal length: 2.25 times the pixels
  const auto zoomed = renderer.render(wider, box.width, box.height, {{1, box.gt}});
  const auto smaller = renderer.render(box.K, 120, 100, {{1, box.gt}});
  ASSERT_FALSE(smaller[0].pixels.empty());
  const auto again = renderer.render(box.K, box.width, box.height, {{1, box.gt}});
  EXPECT_NEAR(double(zoomed[0].pixels.size()) / double(first[0].pixels.size()), 2.25, 0.15);
  EXPECT_LT(smaller[0].pixels.back(), 120u * 100u);
  EXPECT_EQ(again[0].pixels, first[0].pixels);
  EXPECT_EQ(again[0].depth_mm, first[0].depth_mm);
}

TEST(BopVsdRendered, UnknownObjectIsAnInputError) {
  RenderedBox box;
  ModelDepthRenderer renderer({{1, box.mesh}});
  EXPECT_THROW(renderer.render(box.K, box.width, box.height, {{2, box.gt}}), InputError);
}

// One case for tools/bop_toolkit_check.py --vsd-cases: the images as the toolkit holds them
// (dense float32 depth, 0 = none) and binpick's errors.
nlohmann::json toolkit_case(const PartSilhouette& est, const PartSilhouette& gt,
                            const BopDepthImage& test, const Eigen::Matrix3d& K,
                            const VsdSettings& s) {
  auto dense = [&](const PartSilhouette& sil) {
    std::vector<double> d(std::size_t(test.width) * test.height, 0.0);
    for (std::size_t i = 0; i < sil.pixels.size(); ++i) d[sil.pixels[i]] = sil.depth_mm[i];
    return d;
  };
  return {{"width", test.width}, {"height", test.height},
          {"K", {K(0, 0), K(0, 2), K(1, 1), K(1, 2)}},
          {"depth_raw", *test.raw}, {"depth_scale", test.depth_scale},
          {"depth_est", dense(est)}, {"depth_gt", dense(gt)},
          {"delta", s.delta_mm}, {"taus", s.taus},
          {"normalized_by_diameter", s.normalized_by_diameter},
          {"diameter", s.diameter},
          {"errors", vsd_errors(est, gt, test, K, s)}};
}

// The box rendered by Vulkan at the ground truth and at poses near it, against a test image of
// the ground truth with holes and 1 mm steps: the depth arrays eval compares.
std::vector<nlohmann::json> rendered_cases(std::mt19937& rng) {
  RenderedBox box;
  ModelDepthRenderer renderer({{1, box.mesh}});
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<PosedObject> objects{{1, box.gt}};
  for (int k = 0; k < 6; ++k) {
    RigidPose p = box.gt;
    p.t += Eigen::Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5) * 30.0;
    p.R = Eigen::AngleAxisd(0.3 * unit(rng), Eigen::Vector3d::UnitY()).toRotationMatrix() * p.R;
    objects.push_back({1, p});
  }
  const auto renders = renderer.render(box.K, box.width, box.height, objects);
  std::vector<std::uint16_t> raw(std::size_t(box.width) * box.height, 0);
  for (std::size_t i = 0; i < renders[0].pixels.size(); ++i)
    if (unit(rng) > 0.1) raw[renders[0].pixels[i]] = std::uint16_t(std::lround(renders[0].depth_mm[i]));
  const BopDepthImage test{box.width, box.height, &raw, 1.0};
  VsdSettings s;
  s.diameter = box.diameter();
  std::vector<nlohmann::json> out;
  for (std::size_t k = 1; k < renders.size(); ++k)
    out.push_back(toolkit_case(renders[k], renders[0], test, box.K, s));
  return out;
}

// Random images and Vulkan renderings, vsd_errors on them, and tools/bop_toolkit_check.py
// --vsd-cases recomputing them with a numpy transcription of pose_error.vsd, visibility.py and
// misc.depth_im_to_dist_im_fast.
TEST(BopVsdToolkit, RandomAndRenderedImagesAgreeWithTheTranscription) {
  const auto dir = test::fresh_temp_dir("bop_vsd_toolkit");
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  nlohmann::json cases = nlohmann::json::array();
  const std::uint32_t w = 23, h = 17;
  int between = 0;  // errors strictly between 0 and 1: the cases test something
  for (int c = 0; c < 40; ++c) {
    Eigen::Matrix3d K;
    K << 20 + 40 * unit(rng), 0, w * unit(rng), 0, 20 + 40 * unit(rng), h * unit(rng), 0, 0, 1;
    const double scale = c % 2 ? 0.1 : 1.0;
    std::vector<std::uint16_t> raw(w * h);
    for (auto& r : raw) r = unit(rng) < 0.15 ? 0 : std::uint16_t((900 + 200 * unit(rng)) / scale);
    // Renderings: a blob of random depths near the test surface (some in front, some behind).
    auto blob = [&](double offset) {
      PartSilhouette s;
      const double cu = w * unit(rng), cv = h * unit(rng), r = 3 + 6 * unit(rng);
      for (std::uint32_t p = 0; p < w * h; ++p)
        if (std::hypot(p % w - cu, p / w - cv) < r) {
          s.pixels.push_back(p);
          s.depth_mm.push_back(float(950 + offset + 60 * unit(rng)));
        }
      return s;
    };
    const PartSilhouette gt = blob(0), est = blob(40 * unit(rng) - 20);
    VsdSettings s;
    s.diameter = 20 + 100 * unit(rng);
    s.normalized_by_diameter = c % 3 != 0;
    if (!s.normalized_by_diameter) s.taus = {1, 5, 10, 20, 40};
    cases.push_back(toolkit_case(est, gt, {w, h, &raw, scale}, K, s));
    for (double e : cases.back()["errors"]) between += e > 0 && e < 1;
  }
  EXPECT_GT(between, 40);
  for (auto& c : rendered_cases(rng)) {
    for (double e : c["errors"]) between += e > 0 && e < 1;
    cases.push_back(std::move(c));
  }
  EXPECT_GT(between, 70);
  const auto file = dir / "cases.json";
  std::ofstream(file) << cases.dump();
  const std::string cmd = fmt::format(
      "python3 '{}/tools/bop_toolkit_check.py' --vsd-cases '{}' > '{}/check.txt' 2>&1",
      BINPICK_SOURCE_DIR, file.string(), dir.string());
  const int status = std::system(cmd.c_str());
  const std::string check = test::slurp(dir / "check.txt");
  if (WIFEXITED(status) && WEXITSTATUS(status) == 77) GTEST_SKIP() << check;
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << check;
  EXPECT_NE(check.find("VSD: 46 cases"), std::string::npos) << check;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace binpick::eval
