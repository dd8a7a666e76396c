// BOP's VSD: the per-pixel comparison on hand-made images (bop_toolkit pose_error.vsd with the
// "bop19" visibility masks), the rendered model at and off the ground truth, and (with python3
// and numpy) a transcription of the toolkit's functions on random images, within 1e-6.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>

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

// A 4 x 1 image seen from 1 m with a long focal length: distances are depths within 2e-6.
Eigen::Matrix3d narrow_camera() {
  Eigen::Matrix3d K;
  K << 1000, 0, 1.5, 0, 1000, 0, 0, 0, 1;
  return K;
}

struct TinyCase {
  std::vector<std::uint16_t> raw;
  BopDepthImage test() const { return {std::uint32_t(raw.size()), 1, &raw, 1.0}; }
};

VsdSettings settings(std::vector<double> taus, double diameter = 100) {
  VsdSettings s;
  s.taus = std::move(taus);
  s.diameter = diameter;
  return s;
}

TEST(BopVsd, HandComputedFourPixels) {
  // Test depth 1000, 1000, none, 1000. The ground truth covers pixels 0-2 at 1000: all visible
  // (pixel 2 has no depth). The estimate covers 1-3 at 1010, 1000, 1030: visible at 1 (10 mm
  // behind, within delta 15) and 2 (no depth), hidden at 3 (30 mm behind). Union {0, 1, 2},
  // intersection {1, 2} with distances 10 and 0 mm = 0.1 and 0 of the diameter.
  const TinyCase c{{1000, 1000, 0, 1000}};
  const PartSilhouette gt{{0, 1, 2}, {1000, 1000, 1000}};
  const PartSilhouette est{{1, 2, 3}, {1010, 1000, 1030}};
  const auto e = vsd_errors(est, gt, c.test(), narrow_camera(), settings({0.05, 0.2}));
  ASSERT_EQ(e.size(), 2u);
  EXPECT_NEAR(e[0], 2.0 / 3.0, 1e-12);  // pixel 1 misaligned, pixel 0 outside the estimate
  EXPECT_NEAR(e[1], 1.0 / 3.0, 1e-12);  // only pixel 0
}

TEST(BopVsd, EstimateHiddenWhereTheGroundTruthIsVisibleCounts) {
  // Pixel 0: the estimate lies 100 mm behind the test surface, where the ground truth is seen;
  // the toolkit's estimate mask includes it (visib_est |= visib_gt & est rendered), so with tau
  // 200 mm (not normalised) both pixels match: error 0. Without that rule it would be 1/2.
  const TinyCase c{{1000, 1000}};
  const PartSilhouette gt{{0, 1}, {1000, 1000}};
  const PartSilhouette est{{0, 1}, {1100, 1000}};
  VsdSettings s = settings({200, 50});
  s.normalized_by_diameter = false;
  const auto e = vsd_errors(est, gt, c.test(), narrow_camera(), s);
  EXPECT_NEAR(e[0], 0.0, 1e-12);
  EXPECT_NEAR(e[1], 0.5, 1e-12);  // 100 mm >= 50 mm at pixel 0
}

TEST(BopVsd, EqualRenderingsGiveZeroAndNothingVisibleGivesOne) {
  const TinyCase c{{1000, 0, 1000, 1000}};
  const PartSilhouette model{{0, 1, 3}, {990, 1200, 1000}};
  for (double e : vsd_errors(model, model, c.test(), narrow_camera(), settings(bop_vsd_taus())))
    EXPECT_EQ(e, 0.0);
  // Both renderings hidden far behind the test surface: empty union, error 1.
  const PartSilhouette hidden{{0, 2}, {1500, 1500}};
  for (double e : vsd_errors(hidden, hidden, c.test(), narrow_camera(), settings({0.1})))
    EXPECT_EQ(e, 1.0);
  for (double e : vsd_errors({}, {}, c.test(), narrow_camera(), settings({0.1}))) EXPECT_EQ(e, 1.0);
}

TEST(BopVsd, DistancesNotDepthsAreCompared) {
  // Two pixels 0.6 focal lengths off the axis: a depth 20 mm nearer than the test surface is a
  // distance 20 * sqrt(1.36) = 23.3 mm nearer. Tau 22 mm: misaligned by distance, not by depth.
  Eigen::Matrix3d K;
  K << 10, 0, -6, 0, 10, 0, 0, 0, 1;
  const std::vector<std::uint16_t> raw{1000, 1000};
  const BopDepthImage test{2, 1, &raw, 1.0};
  const PartSilhouette gt{{0}, {1000}}, est{{0}, {980}};
  VsdSettings s = settings({22, 24});
  s.normalized_by_diameter = false;
  const auto e = vsd_errors(est, gt, test, K, s);
  EXPECT_EQ(e[0], 1.0);
  EXPECT_EQ(e[1], 0.0);
}

TEST(BopVsd, ToleranceIsInclusive) {
  // One pixel on the optical axis (distance = depth): a model exactly delta = 15 mm behind the
  // test surface is visible (<=), one a float32 step farther is not (then the union is empty).
  Eigen::Matrix3d K;
  K << 500, 0, 0, 0, 500, 0, 0, 0, 1;
  const std::vector<std::uint16_t> raw{1000};
  const BopDepthImage test{1, 1, &raw, 1.0};
  const PartSilhouette at{{0}, {1015.0f}};
  const PartSilhouette beyond{{0}, {std::nextafter(1015.0f, 2000.0f)}};
  EXPECT_EQ(vsd_errors(at, at, test, K, settings({0.05}))[0], 0.0);
  EXPECT_EQ(vsd_errors(beyond, beyond, test, K, settings({0.05}))[0], 1.0);
}

TEST(BopVsd, BadInputIsAnInputError) {
  const TinyCase c{{1000, 1000}};
  const auto K = narrow_camera();
  EXPECT_THROW(vsd_errors({{1, 0}, {1, 1}}, {}, c.test(), K, settings({0.1})), InputError);
  EXPECT_THROW(vsd_errors({{2}, {1}}, {}, c.test(), K, settings({0.1})), InputError);
  EXPECT_THROW(vsd_errors({{0}, {}}, {}, c.test(), K, settings({0.1})), InputError);
  const std::vector<std::uint16_t> small{1};
  EXPECT_THROW(vsd_errors({}, {}, {2, 1, &small, 1.0}, K, settings({0.1})), InputError);
}

TEST(BopVsd, SphereProjectionsOverlapAsTheToolkitApproximates) {
  // Centres 1 m away, 60 mm apart sideways: overlap iff radius * 2 / 1000 > 0.06.
  EXPECT_TRUE(sphere_projections_overlap(31, {0, 0, 1000}, {60, 0, 1000}));
  EXPECT_FALSE(sphere_projections_overlap(30, {0, 0, 1000}, {60, 0, 1000}));
  // Along the same ray at any distance they overlap; a centre at z = 0 never does.
  EXPECT_TRUE(sphere_projections_overlap(1, {10, 10, 1000}, {20, 20, 2000}));
  EXPECT_FALSE(sphere_projections_overlap(100, {0, 0, 0}, {0, 0, 1000}));
}

TEST(BopVsd, ThresholdsAreTheToolkits) {
  const auto taus = bop_vsd_taus();
  ASSERT_EQ(taus.size(), 10u);
  EXPECT_DOUBLE_EQ(taus.front(), 0.05);
  EXPECT_DOUBLE_EQ(taus.back(), 0.5);
  EXPECT_EQ(bop_vsd_thresholds(), taus);
}

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
