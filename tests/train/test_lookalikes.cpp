// Look-alikes (host/train/lookalikes.hpp): the look-alike poses of a part that voting
// confuses and verification must tell apart.
#include <gtest/gtest.h>

#include <cmath>

#include "host/train/lookalikes.hpp"
#include "host/train/surface_sampling.hpp"
#include "host/train/symmetry_detect.hpp"
#include "host/train/voxel_subsample.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick {
namespace {

PointCloud model_points(const Mesh& mesh, float voxel) {
  return voxel_subsample_reference(sample_surface(mesh, 40000), voxel, VoxelFaces::both).cloud;
}

double turn_deg(const Eigen::Isometry3d& S) {
  return Eigen::AngleAxisd(S.linear()).angle() * 180.0 / 3.14159265358979323846;
}

TEST(Lookalikes, ThePlateHasThreeLookAlikeHalfTurns) {
  const Mesh plate = make_builtin_part("plate");  // 120 across, holes laid out without symmetry
  const PartSymmetries exact = find_symmetries(plate);
  ASSERT_TRUE(exact.empty());
  const auto near = find_lookalikes(model_points(plate, 6.0f), 6.0f, exact);
  ASSERT_EQ(near.size(), 3u);
  for (const auto& S : near) {
    EXPECT_NEAR(turn_deg(S), 180.0, 1.0);
    // About the plate's middle: the centre stays (within the holes' pull on the centroid).
    EXPECT_LT(S.translation().norm(), 6.0);
  }
}

TEST(Lookalikes, ExactSymmetriesAreNotRepeated) {
  // A box has exact half turns about its three axes: clustering already merges those poses.
  const Mesh b = test::box({80, 40, 20});
  const PartSymmetries exact = find_symmetries(b);
  ASSERT_EQ(exact.discrete.size(), 3u);
  EXPECT_TRUE(find_lookalikes(model_points(b, 4.0f), 4.0f, exact).empty());
  // Without being told, the same half turns are found as look-alikes (and only they).
  const auto near = find_lookalikes(model_points(b, 4.0f), 4.0f, {});
  EXPECT_EQ(near.size(), 3u);
}

TEST(Lookalikes, AnLBracketHasNone) {
  const Mesh l = test::l_bracket();
  EXPECT_TRUE(find_lookalikes(model_points(l, 2.7f), 2.7f, find_symmetries(l)).empty());
}

TEST(Lookalikes, DegenerateInputsGiveNone) {
  PointCloud few;
  for (int i = 0; i < 5; ++i) few.points.push_back({float(i), 0, 0}), few.normals.push_back({0, 0, 1});
  EXPECT_TRUE(find_lookalikes(few, 1.0f, {}).empty());
  PointCloud no_normals = model_points(test::l_bracket(), 2.7f);
  no_normals.normals.clear();
  EXPECT_TRUE(find_lookalikes(no_normals, 2.7f, {}).empty());
  EXPECT_TRUE(find_lookalikes(model_points(test::l_bracket(), 2.7f), 0.0f, {}).empty());
}

}  // namespace
}  // namespace binpick
