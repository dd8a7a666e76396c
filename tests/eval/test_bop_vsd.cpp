// BOP's VSD: the per-pixel comparison on hand-made images (bop_toolkit pose_error.vsd with the
// "bop19" visibility masks, distances from the camera centre) and the toolkit's thresholds.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "host/core/error.hpp"
#include "host/eval/metrics/bop_vsd.hpp"

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

}  // namespace
}  // namespace binpick::eval
