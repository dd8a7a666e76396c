// The flat-region test (host/detect/hypotheses/flat_region.hpp): region sizes on clouds of known geometry,
// and a detection where the highest points lie on a sheet wider than any face of the part.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "host/app/options/model_options.hpp"
#include "host/detect/detector.hpp"
#include "host/detect/hypotheses/flat_region.hpp"
#include "host/eval/metrics/pose_error.hpp"
#include "host/train/ppf_model.hpp"
#include "tests/support/rendered_parts.hpp"
#include "tests/support/test_meshes.hpp"

using namespace binpick;

namespace {

// A square grid of (2 half + 1)^2 points, spacing 1 mm, at height z, normals along +z (or -z).
void add_grid(PointCloud& c, int half, float z, float nz = 1) {
  for (int x = -half; x <= half; ++x)
    for (int y = -half; y <= half; ++y) {
      c.points.emplace_back(float(x), float(y), z);
      c.normals.emplace_back(0.0f, 0.0f, nz);
    }
}

FlatRegionOptions options(float radius) {
  FlatRegionOptions o;
  o.radius = radius;
  o.tolerance = 0.5f;
  o.link = 1.5f;
  return o;
}

// Grid points within r of the origin (the region a flat grid gives from its centre).
std::size_t grid_points_within(int half, float r) {
  std::size_t n = 0;
  for (int x = -half; x <= half; ++x)
    for (int y = -half; y <= half; ++y) n += float(x * x + y * y) <= r * r;
  return n;
}

}  // namespace

TEST(FlatRegion, OnAPlaneIsEveryPointWithinTheRadius) {
  PointCloud c;
  add_grid(c, 20, 0);
  const FlatRegions regions(c, options(10.5f));
  const std::size_t centre = nearest_point(c, Eigen::Vector3f::Zero());
  EXPECT_EQ(c.points[centre], Eigen::Vector3f::Zero());
  EXPECT_EQ(regions.size_from(centre), grid_points_within(20, 10.5f));
  EXPECT_EQ(regions.largest(), grid_points_within(20, 10.5f));
}

TEST(FlatRegion, StaysOnItsPlaneAndOffTheOtherFace) {
  PointCloud c;
  add_grid(c, 20, 0);
  add_grid(c, 20, 3);       // a parallel plane 3 mm off (beyond the tolerance)
  add_grid(c, 20, 0, -1);   // the other face of a sheet, at the same place: normals opposite
  const FlatRegions regions(c, options(100));
  EXPECT_EQ(regions.size_from(0), 41u * 41u);
  EXPECT_EQ(regions.largest(), 41u * 41u);
}

TEST(FlatRegion, AGapWiderThanTheLinkEndsIt) {
  PointCloud c;
  add_grid(c, 5, 0);
  const std::size_t one = c.points.size();
  for (std::size_t i = 0; i < one; ++i) {  // the same grid 12 mm along x: 2 mm between them
    c.points.push_back(c.points[i] + Eigen::Vector3f(12, 0, 0));
    c.normals.push_back(c.normals[i]);
  }
  const FlatRegions regions(c, options(100));
  EXPECT_EQ(regions.size_from(0), one);
  FlatRegionOptions wide = options(100);
  wide.link = 2.5f;
  EXPECT_EQ(FlatRegions(c, wide).size_from(0), 2 * one);
}

TEST(FlatRegion, OnACylinderIsAStripAlongItsAxis) {
  // Radius 10 mm, 1 mm apart along the axis and about 1 mm around: the tangent plane holds
  // the points within acos(1 - 0.5 / 10), about 18 degrees, of the seed's line on either side.
  PointCloud c;
  const int around = 63;
  for (int a = 0; a < around; ++a)
    for (int x = -20; x <= 20; ++x) {
      const double phi = 2 * std::numbers::pi * a / around;
      c.points.emplace_back(float(x), float(10 * std::cos(phi)), float(10 * std::sin(phi)));
      c.normals.emplace_back(0.0f, float(std::cos(phi)), float(std::sin(phi)));
    }
  const FlatRegions regions(c, options(100));
  const std::size_t strip = regions.size_from(20);  // a = 0, x = 0
  // Lines at 0 and +-1 step (5.7 degrees apart) and +-2 (11.4 degrees, 0.2 mm off the plane),
  // +-3 (17.1 degrees, 0.44 mm) in, +-4 (22.9 degrees: 0.79 mm off, and past 20 degrees) out.
  EXPECT_EQ(strip, 7u * 41u);
  EXPECT_EQ(regions.largest(), 7u * 41u);
}

TEST(FlatRegion, DegenerateClouds) {
  PointCloud one;
  one.points.emplace_back(1.0f, 2.0f, 3.0f);
  one.normals.emplace_back(0.0f, 0.0f, 1.0f);
  EXPECT_EQ(FlatRegions(one, options(10)).size_from(0), 1u);
  EXPECT_EQ(FlatRegions(one, options(10)).largest(), 1u);
  EXPECT_EQ(FlatRegions(PointCloud{}, options(10)).largest(), 0u);
  // Zero radius: the seed alone.
  PointCloud c;
  add_grid(c, 3, 0);
  EXPECT_EQ(FlatRegions(c, options(0)).size_from(5), 1u);
}


// A 50 x 50 mm sheet lies 40 mm nearer the camera than a shaft, beside it: the highest points
// come first on the sheet. With the flat-region test those are skipped and the next, on the
// shaft, voted on; without it the one hypothesis of the first round votes on the sheet.
TEST(FlatRegion, AHighestPointOnASheetWiderThanThePartIsSkipped) {
  Eigen::Isometry3f S = Eigen::Isometry3f::Identity();
  S.translation() = Eigen::Vector3f(60, -25, 560);
  const test::ShaftBeside shaft = test::shaft_beside({-70, 10, 600}, test::box({50, 50, 2}), S);
  const test::RenderedScene& scene = shaft.scene;
  const PpfModel& model = shaft.model;
  for (int path = 0; path < 2; ++path) {
    SCOPED_TRACE(path == 0 ? "depth image" : "cloud");
    DetectParams p;
    p.hypotheses = 1;
    // On the image one highest point is sought, and the stand-in is found when the first is
    // skipped; a cloud's highest points are all found at once (twice those sought), and its
    // second is on the sheet too: there 2 are sought and the first round takes one.
    p.more_hypotheses = path == 0 ? 0 : 1;
    p.confident = 0;  // no second round
    p.prerank = false;  // height order: the sheet's points come first
    for (const double flat : {0.0, p.flat_region}) {
      DetectParams q = p;
      q.flat_region = flat;
      Detector detector(model, q);
      const auto found =
          path == 0 ? detector.detect(scene.depth, scene.cam) : detector.detect(scene.cloud);
      ASSERT_EQ(found.size(), 1u);
      const eval::PoseError e = shaft.error_of(found[0]);
      if (flat == 0) {
        EXPECT_GT(e.translation_mm, 0.5 * model.diameter);  // on the sheet
        EXPECT_TRUE(detector.skipped().empty());
      } else {
        EXPECT_LT(e.translation_mm, 0.05 * model.diameter);
        EXPECT_LT(e.rotation_deg, 5.0);
        ASSERT_FALSE(detector.skipped().empty());
        EXPECT_NE(detector.skipped()[0].reason.find("flat region"), std::string::npos)
            << detector.skipped()[0].reason;
      }
    }
  }
}

// The skip rule alone (FlatRegionSkip): a point on a plane wider than the part's widest face is
// skipped with its reason; one on a patch as small as the part's face is kept; off for ratio 0
// and for thin parts. The part: a 7 x 7 mm face (1 mm voxels); the scene: a 41 x 41 mm sheet.
TEST(FlatRegion, TheSkipRuleComparesWithThePartsWidestFace) {
  PointCloud part, sheet, patch;
  add_grid(part, 3, 0.0f);
  add_grid(sheet, 20, 100.0f, -1.0f);
  add_grid(patch, 3, 100.0f, -1.0f);
  const float diameter = 20.0f, voxel = 1.0f;
  const FlatRegionSkip skip(part, diameter, voxel, 1.25, false);
  const std::string why = skip.reason(sheet, {0.0f, 0.0f, 100.0f}, 0.0, 1.0);
  EXPECT_NE(why.find("skipped: the highest point lies on a flat region of"), std::string::npos)
      << why;
  EXPECT_NE(why.find("part's widest (49 points)"), std::string::npos) << why;
  EXPECT_EQ(skip.reason(patch, {0.0f, 0.0f, 100.0f}, 0.0, 1.0), "");
  EXPECT_EQ(FlatRegionSkip(part, diameter, voxel, 0.0, false).reason(sheet, {0, 0, 100}, 0, 1), "");
  EXPECT_EQ(FlatRegionSkip(part, diameter, voxel, 1.25, true).reason(sheet, {0, 0, 100}, 0, 1), "");
  EXPECT_EQ(skip.reason(PointCloud{}, {0, 0, 100}, 0, 1), "");
}
