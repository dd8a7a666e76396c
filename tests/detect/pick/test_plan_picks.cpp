// Pick planning (host/detect/pick/plan_picks.hpp) on a hand-made scene: a floor seen straight
// down, detections whose one suction grasp is clear, under something, outside the approach cone
// or against the bin's wall; and the order of the picks (--pick-score 0.7 here).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "host/detect/pick/plan_picks.hpp"
#include "host/detect/scene/cloud_image.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;
using binpick::test::test_device;

namespace {

constexpr std::uint32_t kSize = 240;
const bp_camera kCam{400, 400, kSize / 2.0f, kSize / 2.0f, 1, kSize, kSize, 0};

// A floor at 600 mm under the whole view, as a point image.
std::vector<float> floor_points() {
  std::vector<float> xyzw(4 * kSize * kSize);
  for (std::uint32_t v = 0; v < kSize; ++v)
    for (std::uint32_t u = 0; u < kSize; ++u) {
      float* p = &xyzw[4 * (v * kSize + u)];
      p[0] = (u - kCam.cx) * 600 / kCam.fx;
      p[1] = (v - kCam.cy) * 600 / kCam.fy;
      p[2] = 600;
      p[3] = 1;
    }
  return xyzw;
}

// Raises the pixels within r mm of (x, y) on the floor to depth z: something lying there.
void raise(std::vector<float>& xyzw, double x, double y, double r, float z) {
  for (std::uint32_t v = 0; v < kSize; ++v)
    for (std::uint32_t u = 0; u < kSize; ++u) {
      float* p = &xyzw[4 * (v * kSize + u)];
      if (std::hypot(p[0] - x, p[1] - y) > r) continue;
      p[0] = p[0] * z / 600;
      p[1] = p[1] * z / 600;
      p[2] = z;
    }
}

Detection at(double x, double y, double z, double score,
             const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Detection d;
  d.R = R;
  d.t = {x, y, z};
  d.breakdown.factor[0] = score;
  return d;
}

// One suction grasp at the model's origin, approaching along the model's z (the camera's view).
const std::vector<Grasp> kGrasps{[] {
  Grasp g;
  g.size = 10;
  g.closing = across(g.approach);
  return g;
}()};

PickOptions options() {
  PickOptions o;
  o.min_score = 0.7;
  o.approach_cone = 45;
  o.tolerance = 1;
  o.part_diameter = 50;
  return o;
}

std::vector<PlannedPick> plan(const std::vector<float>& xyzw, const std::vector<Detection>& d,
                              const BinFit* bin = nullptr) {
  const ocl::Buffer<float> points(test_device(), std::span<const float>(xyzw));
  return plan_picks(test_device(), points, kCam, d, kGrasps, Gripper::suction(10, 5, 10, 100), bin,
                    options());
}

TEST(PlanPicks, EachDetectionItsClearGraspOrTheReasonWhyNot) {
  std::vector<float> xyzw = floor_points();
  raise(xyzw, -60, 0, 4, 560);  // a part lying over the grasp of the detection at (-60, 0)
  const std::vector<Detection> d{
      at(0, 0, 590, 0.9),
      at(-60, 0, 590, 0.95),
      at(60, 0, 590, 0.9, Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitX()).toRotationMatrix()),
      at(0, 60, 590, 0.5),
  };
  ASSERT_NEAR(d[1].score(), 0.95, 1e-12);
  const auto picks = plan(xyzw, d);
  ASSERT_EQ(picks.size(), 4u);
  EXPECT_TRUE(picks[0].picked) << picks[0].reason;
  EXPECT_EQ(picks[0].order, 1u);
  EXPECT_NEAR(picks[0].clearance, 12.5, 1e-6);  // nothing near: the cap, a quarter diameter
  EXPECT_TRUE(picks[0].pose.translation().isApprox(Eigen::Vector3d(0, 0, 590)));
  EXPECT_FALSE(picks[1].picked);  // under another part, however sure
  EXPECT_NE(picks[1].reason.find("1 collide with what the camera sees"), std::string::npos)
      << picks[1].reason;
  EXPECT_FALSE(picks[2].picked);
  EXPECT_EQ(picks[2].reason, "every grasp's approach is more than 45 degrees from down");
  EXPECT_FALSE(picks[3].picked);
  EXPECT_EQ(picks[3].reason, "score 0.50 below --pick-score 0.70");
}

TEST(PlanPicks, AGripperThatWouldHitTheWallIsRefusedWithThatReason) {
  // A bin of 100 x 100 x 100 whose floor is the view's floor, up towards the camera.
  BinFit bin;
  bin.found = true;
  bin.axes.col(0) = Eigen::Vector3d(1, 0, 0);
  bin.axes.col(1) = Eigen::Vector3d(0, -1, 0);
  bin.axes.col(2) = Eigen::Vector3d(0, 0, -1);
  bin.origin = {0, 0, 600};
  bin.interior = {100, 100, 100};
  const std::vector<Detection> d{at(47, 0, 590, 0.9), at(40, 0, 590, 0.9)};
  const auto picks = plan(floor_points(), d, &bin);
  EXPECT_FALSE(picks[0].picked);  // the cup (radius 5) reaches x = 52, past the wall at 50
  EXPECT_NE(picks[0].reason.find("1 hit the bin's wall"), std::string::npos) << picks[0].reason;
  EXPECT_TRUE(picks[1].picked) << picks[1].reason;
  // Sunk into the floor: refused too.
  EXPECT_NE(plan(floor_points(), {at(0, 0, 605, 0.9)}, &bin)[0].reason.find("the bin's floor"),
            std::string::npos);
}

TEST(PlanPicks, OrderedByScoreThenClearanceAndHeight) {
  std::vector<float> xyzw = floor_points();
  // Something beside the grasp at (0, 0): its nearest pixel at y = 10.5 mm on the floor (a pixel
  // is 1.5 mm there), 9.975 mm at its height, 4.975 mm from the cup's side.
  raise(xyzw, 0, 14, 4, 570);
  const std::vector<Detection> d{at(0, 0, 590, 0.75), at(60, 0, 590, 0.75), at(-60, 0, 570, 0.75),
                                 at(0, -60, 590, 0.99), at(0, 60, 590, 0.80)};
  const auto picks = plan(xyzw, d);
  for (const auto& p : picks) ASSERT_TRUE(p.picked) << p.reason;
  EXPECT_LT(picks[0].clearance, 12.5);
  EXPECT_NEAR(picks[0].clearance, 4.975, 1e-3);
  // The surest first; 0.05 surer comes before higher and clearer; of equal scores the higher,
  // then the clearer.
  EXPECT_EQ(picks[3].order, 1u);
  EXPECT_EQ(picks[4].order, 2u);
  EXPECT_EQ(picks[2].order, 3u);
  EXPECT_EQ(picks[1].order, 4u);
  EXPECT_EQ(picks[0].order, 5u);
}

TEST(PlanPicks, NoGraspOfTheGrippersKind) {
  const ocl::Buffer<float> points(test_device(), std::span<const float>(floor_points()));
  const auto picks = plan_picks(test_device(), points, kCam, {at(0, 0, 590, 0.9)}, kGrasps,
                                Gripper::parallel(6, 10, 40, 8), nullptr, options());
  EXPECT_EQ(picks[0].reason, "no parallel grasp");
  EXPECT_TRUE(plan(floor_points(), {}).empty());
}

}  // namespace

TEST(PlanPicks, ThroughACloudsVirtualCameraAPartUnderAnotherIsRefused) {
  // The same floor and the part lying over a grasp, as an unorganised cloud (detect --cloud):
  // seen through the virtual camera verification uses, a millimetre a pixel.
  std::vector<float> xyzw = floor_points();
  raise(xyzw, -60, 0, 4, 560);
  PointCloud cloud;
  for (std::size_t i = 0; i < xyzw.size(); i += 4)
    cloud.points.emplace_back(xyzw[i], xyzw[i + 1], xyzw[i + 2]);
  const CloudImage image = cloud_point_image(cloud, 1.0f);
  const ocl::Buffer<float> points(test_device(), std::span<const float>(image.points.xyzw));
  const auto picks =
      plan_picks(test_device(), points, image.camera, {at(0, 0, 590, 0.9), at(-60, 0, 590, 0.95)},
                 kGrasps, Gripper::suction(10, 5, 10, 100), nullptr, options());
  EXPECT_TRUE(picks[0].picked) << picks[0].reason;
  EXPECT_EQ(picks[0].order, 1u);
  EXPECT_FALSE(picks[1].picked);
  EXPECT_NE(picks[1].reason.find("1 collide with what the camera sees"), std::string::npos)
      << picks[1].reason;
}
