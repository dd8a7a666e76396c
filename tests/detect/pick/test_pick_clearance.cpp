// The pick_clearance kernel against its C++ reference on random point images and grippers, and
// the signed distance it rests on against hand-computed cases (host/detect/pick/pick_clearance).
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "host/core/gripper.hpp"
#include "host/detect/pick/pick_clearance.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;
using binpick::test::test_device;

namespace {

bp_camera camera(std::uint32_t w, std::uint32_t h) { return {400, 400, w / 2.0f, h / 2.0f, 1, w, h, 0}; }

// A random point image of a bumpy surface near 500 mm, a quarter of the pixels without depth.
std::vector<float> random_points(const bp_camera& cam, std::mt19937& rng) {
  std::uniform_real_distribution<float> bump(-30, 30), coin(0, 1);
  std::vector<float> xyzw(4 * std::size_t(cam.width) * cam.height, 0.0f);
  for (std::uint32_t v = 0; v < cam.height; ++v)
    for (std::uint32_t u = 0; u < cam.width; ++u) {
      if (coin(rng) < 0.25f) continue;
      const float z = 500 + bump(rng);
      float* p = &xyzw[4 * (std::size_t(v) * cam.width + u)];
      p[0] = (u - cam.cx) * z / cam.fx;
      p[1] = (v - cam.cy) * z / cam.fy;
      p[2] = z;
      p[3] = 1;
    }
  return xyzw;
}

// A grasp frame on the surface, its approach within 40 degrees of the view axis.
Eigen::Isometry3d random_grasp(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Isometry3d g = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  g.linear() = Eigen::AngleAxisd(0.7 * u(rng), axis).toRotationMatrix();
  g.translation() = Eigen::Vector3d(60 * u(rng), 40 * u(rng), 490 + 20 * u(rng));
  return g;
}

TEST(PickClearance, KernelMatchesReferenceOnRandomScenesAndGrippers) {
  std::mt19937 rng(7);
  const bp_camera cam = camera(160, 120);
  const std::vector<float> points = random_points(cam, rng);
  const ocl::Buffer<float> device(test_device(), std::span<const float>(points));
  const Gripper grippers[] = {Gripper::suction(10, 5, 12, 80), Gripper::parallel(6, 10, 30, 8)};
  std::vector<bp_pick_candidate> candidates;
  std::uniform_real_distribution<double> width(5, 40);
  for (int k = 0; k < 200; ++k) {
    const Gripper& gripper = grippers[k % 2];
    Grasp grasp;
    grasp.kind = gripper.kind;
    grasp.size = width(rng);
    candidates.push_back(
        pick_candidate(gripper.solids(grasp), random_grasp(rng), cam, 1.5f, k % 3 ? 13.0f : 0.5f));
  }
  const auto kernel = pick_clearance(test_device(), device, cam, candidates);
  const auto reference = pick_clearance_reference(points, cam, candidates);
  ASSERT_EQ(kernel.size(), reference.size());
  std::size_t colliding = 0, clear = 0;
  for (std::size_t k = 0; k < kernel.size(); ++k) {
    // The same float operations in the same order (FP_CONTRACT OFF): the same results.
    EXPECT_EQ(kernel[k].colliding, reference[k].colliding) << k;
    EXPECT_EQ(kernel[k].clearance, reference[k].clearance) << k;
    colliding += reference[k].colliding > 0;
    clear += reference[k].colliding == 0 && reference[k].clearance < candidates[k].cap;
  }
  // The premise: both outcomes occur, and clearances below the cap.
  EXPECT_GT(colliding, 20u);
  EXPECT_GT(clear, 5u);
}

TEST(PickClearance, DegenerateInputs) {
  const bp_camera cam = camera(40, 30);
  std::vector<float> empty(4 * 40 * 30, 0.0f);
  const ocl::Buffer<float> device(test_device(), std::span<const float>(empty));
  EXPECT_TRUE(pick_clearance(test_device(), device, cam, {}).empty());  // no candidate
  Grasp grasp;
  const auto c = pick_candidate(Gripper::suction(10, 5, 10, 50).solids(grasp),
                                Eigen::Isometry3d(Eigen::Translation3d(0, 0, 500)), cam, 1, 13);
  // An image without a point: nothing collides, the clearance is the cap.
  const auto r = pick_clearance(test_device(), device, cam, {c, c});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].colliding, 0u);
  EXPECT_EQ(r[0].clearance, 13.0f);
  // Behind the camera: the window is the whole image, still nothing.
  const auto behind = pick_candidate(Gripper::suction(10, 5, 10, 50).solids(grasp),
                                     Eigen::Isometry3d(Eigen::Translation3d(0, 0, -100)), cam, 1, 13);
  EXPECT_EQ(behind.rect[2], 40u);
  EXPECT_EQ(pick_clearance(test_device(), device, cam, {behind})[0].colliding, 0u);
}

TEST(PickClearance, ASuctionCupOnAFlatFaceTouchesNothingAndAPostInsideItCollides) {
  // A flat floor at 500 mm seen straight down; a cup of 10 mm at its middle, approaching down.
  const bp_camera cam = camera(100, 100);
  std::vector<float> xyzw(4 * 100 * 100, 0.0f);
  for (std::uint32_t v = 0; v < 100; ++v)
    for (std::uint32_t u = 0; u < 100; ++u) {
      float* p = &xyzw[4 * (v * 100 + u)];
      p[2] = 500;
      p[0] = (u - cam.cx) * 500 / cam.fx;
      p[1] = (v - cam.cy) * 500 / cam.fy;
      p[3] = 1;
    }
  Grasp grasp;
  const auto solids = Gripper::suction(10, 5, 10, 50).solids(grasp);
  const Eigen::Isometry3d at(Eigen::Translation3d(0, 0, 500));  // z (approach) = the view axis
  const bp_pick_candidate c = pick_candidate(solids, at, cam, 1, 13);
  auto r = pick_clearance_reference(xyzw, cam, {c});
  EXPECT_EQ(r[0].colliding, 0u);
  EXPECT_EQ(r[0].clearance, 13.0f);  // the floor itself is the grasp's plane: not an obstacle
  // A post 20 mm high under the cup's rim: its top is inside the gripper.
  float* post = &xyzw[4 * (50 * 100 + 55)];  // 6.25 mm from the axis at 500 mm: outside the cup
  post[2] = 480;
  post[0] = (55 - cam.cx) * 480 / cam.fx;
  r = pick_clearance_reference(xyzw, cam, {c});
  EXPECT_EQ(r[0].colliding, 0u);
  EXPECT_NEAR(r[0].clearance, 1.0, 1e-3);  // 6 mm from the axis: 1 mm beside the body
  float* inside = &xyzw[4 * (50 * 100 + 52)];  // 2.5 mm from the axis, 20 mm up
  inside[2] = 480;
  inside[0] = (52 - cam.cx) * 480 / cam.fx;
  r = pick_clearance_reference(xyzw, cam, {c});
  EXPECT_EQ(r[0].colliding, 1u);
}

TEST(GripperSolids, SignedDistancesByHand) {
  const GripperSolid box{GripperSolid::Shape::box, {0, 0, 0}, {1, 2, 3}};
  EXPECT_DOUBLE_EQ(signed_distance(box, {0, 0, 0}), -1);     // nearest face: x
  EXPECT_DOUBLE_EQ(signed_distance(box, {4, 0, 0}), 3);
  EXPECT_DOUBLE_EQ(signed_distance(box, {4, 6, 0}), 5);      // to the edge (1, 2): 3-4-5
  const GripperSolid cylinder{GripperSolid::Shape::cylinder, {0, 0, -10}, {5, 5, 10}};
  EXPECT_DOUBLE_EQ(signed_distance(cylinder, {0, 0, -10}), -5);
  EXPECT_DOUBLE_EQ(signed_distance(cylinder, {8, 0, -10}), 3);
  EXPECT_DOUBLE_EQ(signed_distance(cylinder, {0, 0, 2}), 2);
  // A suction tool: the cup from the grasp point up, the body above it.
  Grasp suction;
  const auto s = Gripper::suction(10, 4, 20, 100).solids(suction);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_DOUBLE_EQ(signed_distance(s[0], {0, 0, 0}), 0);       // the cup's lip on the point
  EXPECT_DOUBLE_EQ(signed_distance(s[1], {0, 0, -104}), 0);    // the body's top
  // A parallel gripper's fingers stand beside the opening.
  Grasp jaws;
  jaws.kind = Grasp::Kind::parallel;
  jaws.size = 30;
  const auto p = Gripper::parallel(6, 10, 40, 8).solids(jaws);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_DOUBLE_EQ(signed_distance(p[0], {15, 0, 0}), 0);      // the right finger's pad
  EXPECT_DOUBLE_EQ(signed_distance(p[1], {-15, 0, 0}), 0);
  EXPECT_GT(signed_distance(p[0], {0, 0, 0}), 14.9);           // the opening is free
  EXPECT_THROW(Gripper::parallel(6, 10, 40, 8).solids(suction), std::logic_error);
}

}  // namespace
