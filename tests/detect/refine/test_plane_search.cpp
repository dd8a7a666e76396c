// The in-plane search of thin parts (host/detect/refine/plane_search.hpp, kernels/plane_search.cl): the
// edge step scores of the device against the C++ reference on random poses, the in-plane pose
// arithmetic, and on an image of the built-in plate lying on a plane one sheet thickness beneath
// it, a start shifted and turned in the plate's plane is brought back to the right pose, also
// under depth noise of one thickness on the low-passed depth (search_reads_lowpass).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <span>

#include "host/core/error.hpp"
#include "host/detect/refine/plane_search.hpp"
#include "host/detect/scene/scene_lowpass.hpp"
#include "host/train/edge_probes.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/probe_surface.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "tests/support/plate_scene.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;

namespace {

const PpfModel& plate_model() {
  static const PpfModel model =
      train_ppf_model(make_builtin_part("plate"), PpfTrainParams{}, nullptr, test::test_device());
  return model;
}

Eigen::Vector3d centroid(const PointCloud& c) {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (const auto& p : c.points) s += p.cast<double>();
  return s / double(c.points.size());
}

// The plate's search model on the device: its edge probes and surface points, turned about
// their centroid.
PlaneSearchModel plate_search_model(ocl::Device& dev) {
  const PpfModel& model = plate_model();
  return upload_plane_search_model(dev, model.edge_probes, model.cloud, centroid(model.cloud));
}

double angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

}  // namespace

TEST(PlaneSearch, InPlanePoseTurnsAboutTheCentreAndShiftsInThePlane) {
  const Eigen::Isometry3d pose = test::plate_pose();
  const Eigen::Vector3d axis(0, 0, 1), centre(3, -2, 0.5);
  const Eigen::Isometry3d same = in_plane_pose(pose, axis, centre, 0, 0, 0);
  EXPECT_TRUE(same.isApprox(pose, 1e-12));
  const Eigen::Isometry3d moved = in_plane_pose(pose, axis, centre, 0.7, 4.0, -3.0);
  // The sheet's normal is kept, the centre moves 5 mm within the plane, the turn is 0.7 rad.
  EXPECT_LT((moved.linear() * axis - pose.linear() * axis).norm(), 1e-12);
  const Eigen::Vector3d d = moved * centre - pose * centre;
  EXPECT_NEAR(d.norm(), 5.0, 1e-9);
  EXPECT_NEAR(d.dot(pose.linear() * axis), 0.0, 1e-9);
  EXPECT_NEAR(angle_between(moved.linear(), pose.linear()), 0.7, 1e-9);
}

TEST(PlaneSearch, EdgeStepScoresMatchReference) {
  auto& dev = test::test_device();
  const PpfModel& model = plate_model();
  const bp_camera cam = test::plate_camera();
  const Eigen::Isometry3d pose = test::plate_pose();
  const PointImage image = test::plate_over_plane(cam, pose, true);
  const ocl::Buffer<float> points(dev, std::span<const float>(image.xyzw));
  const ocl::Buffer<float> depth = point_depths(dev, points, cam);
  // The depth image is copied exactly (the plate's holes without depth give zeros).
  const std::vector<float> want_depth = point_depths_reference(image.xyzw);
  EXPECT_EQ(depth.read(dev), want_depth);
  EXPECT_GT(std::count(want_depth.begin(), want_depth.end(), 0.0f), 0);
  const PlaneSearchModel sm = plate_search_model(dev);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::vector<Eigen::Isometry3d> poses = {pose};
  for (int k = 0; k < 200; ++k)
    poses.push_back(in_plane_pose(pose, sm.axis, sm.centre, std::numbers::pi * U(rng),
                                  30 * U(rng), 30 * U(rng)));
  Eigen::Isometry3d behind = pose;  // behind the camera: no probe counts
  behind.translation().z() = -500;
  poses.push_back(behind);
  for (std::uint32_t stride : {1u, 8u}) {
    const std::vector<float> got = edge_step_scores(dev, depth, cam, sm, poses, stride, 4.8f);
    PointCloud all = model.edge_probes;
    all.points.insert(all.points.end(), model.cloud.points.begin(), model.cloud.points.end());
    all.normals.insert(all.normals.end(), model.cloud.normals.begin(), model.cloud.normals.end());
    const std::vector<float> want = edge_step_scores_reference(
        image.xyzw, cam, all, model.edge_probes.points.size(), poses, stride, 4.8f);
    ASSERT_EQ(got.size(), want.size());
    // Floats: a probe projected within rounding of a pixel edge may read the neighbour pixel.
    int differ = 0;
    for (std::size_t k = 0; k < got.size(); ++k)
      if (std::fabs(got[k] - want[k]) > 1e-4f) ++differ;
    EXPECT_LE(differ, 4) << stride;
    EXPECT_EQ(got.back(), -1.0f);
    EXPECT_GT(got.front(), 1.0f);  // the right pose: the step down to the plane (1.5 mm)
  }
  EXPECT_THROW(edge_step_scores(dev, depth, cam, sm, poses, 0, 4.8f), InputError);
  EXPECT_THROW(edge_step_scores(dev, points, cam, sm, poses, 1, 4.8f), InputError);  // float4s
  EXPECT_THROW(point_depths(dev, depth, cam), InputError);  // not a point image
  EXPECT_TRUE(edge_step_scores(dev, depth, cam, sm, {}, 1, 4.8f).empty());
  PointCloud no_normals = model.edge_probes;
  no_normals.normals.clear();
  EXPECT_THROW(upload_plane_search_model(dev, no_normals, model.cloud, sm.centre), InputError);
}

// No depth anywhere: every edge probe counts a full tolerance (a shadow or a drop), every point
// of the part's own surface half of one (the void beside a pile or the sensor's loss on real
// surface: kernels/plane_search.cl), so the score is half the tolerance, on the device and in
// the reference.
TEST(PlaneSearch, NoDepthCountsAFullToleranceAtTheEdgesAndHalfUnderThePart) {
  auto& dev = test::test_device();
  const PpfModel& model = plate_model();
  const bp_camera cam = test::plate_camera();
  const std::vector<float> empty(4 * std::size_t(cam.width) * cam.height, 0.0f);
  const ocl::Buffer<float> points(dev, std::span<const float>(empty));
  const PlaneSearchModel sm = plate_search_model(dev);
  const std::vector<Eigen::Isometry3d> poses = {test::plate_pose()};
  const float got = edge_step_scores(dev, point_depths(dev, points, cam), cam, sm, poses, 1, 4.8f)[0];
  EXPECT_NEAR(got, 2.4f, 1e-4f);  // float sums over a few thousand probes
  PointCloud all = model.edge_probes;
  all.points.insert(all.points.end(), model.cloud.points.begin(), model.cloud.points.end());
  all.normals.insert(all.normals.end(), model.cloud.normals.begin(), model.cloud.normals.end());
  EXPECT_NEAR(edge_step_scores_reference(empty, cam, all, model.edge_probes.points.size(), poses,
                                         1, 4.8f)[0],
              2.4f, 1e-4f);
}

TEST(PlaneSearch, FindsThePlateShiftedAndTurnedOnAPlate) {
  auto& dev = test::test_device();
  const bp_camera cam = test::plate_camera();
  const Eigen::Isometry3d pose = test::plate_pose();
  const PlaneSearchModel sm = plate_search_model(dev);
  // The sheet's normal is the plate's thin axis (z in the model frame).
  EXPECT_GT(std::fabs(sm.axis.z()), 0.99);
  for (bool holes_without_depth : {false, true}) {
    const PointImage image = test::plate_over_plane(cam, pose, holes_without_depth);
    const ocl::Buffer<float> points(dev, std::span<const float>(image.xyzw));
    const ocl::Buffer<float> depth = point_depths(dev, points, cam);
    // Shifted 9 mm and 6 mm in the plane and turned 25 degrees: on the plane beneath, its
    // surface still fits; the search brings it back within the probes' margin (3 mm beyond the
    // edges: closer than that, every probe still sees the step) and a fine step. The right
    // pose, searched in the same batch, finds nothing better far away.
    const Eigen::Isometry3d start = in_plane_pose(pose, sm.axis, sm.centre, 25 * std::numbers::pi / 180, 9, -6);
    const std::vector<PlaneSearchResult> found =
        plane_search(dev, depth, cam, sm, {start, pose}, 18.0, 4.8f);
    ASSERT_EQ(found.size(), 2u);
    EXPECT_GT(found[0].score, found[0].start_score + 0.3f) << holes_without_depth;
    EXPECT_LT((found[0].pose * sm.centre - pose * sm.centre).norm(), 5.0) << holes_without_depth;
    EXPECT_LT(angle_between(found[0].pose.linear(), pose.linear()) * 180 / std::numbers::pi, 3.0)
        << holes_without_depth;
    EXPECT_LT((found[1].pose * sm.centre - pose * sm.centre).norm(), 5.0);
    // Searched alone, a start gives what it gives in the batch.
    const std::vector<PlaneSearchResult> alone = plane_search(dev, depth, cam, sm, {start}, 18.0, 4.8f);
    ASSERT_EQ(alone.size(), 1u);
    EXPECT_EQ(alone[0].score, found[0].score);
    EXPECT_TRUE(alone[0].pose.isApprox(found[0].pose));
  }
  // No span: the start is returned; no starts: no results.
  const PointImage image = test::plate_over_plane(cam, pose, false);
  const ocl::Buffer<float> points(dev, std::span<const float>(image.xyzw));
  const ocl::Buffer<float> depth = point_depths(dev, points, cam);
  const std::vector<PlaneSearchResult> none = plane_search(dev, depth, cam, sm, {pose}, 0.0, 4.8f);
  ASSERT_EQ(none.size(), 1u);
  EXPECT_TRUE(none[0].pose.isApprox(pose));
  EXPECT_EQ(none[0].score, none[0].start_score);
  EXPECT_TRUE(plane_search(dev, depth, cam, sm, {}, 18.0, 4.8f).empty());
}

// The memo of one image's searches (a second round of hypotheses brings the first round's
// starts again, in front): the starts it holds are not searched again, the results are those of
// searching all the starts, and a start that differs from the memo's at its position is searched
// afresh with everything after it.
TEST(PlaneSearch, MemoReusesTheStartsItHoldsAndEqualsASearchOfAll) {
  auto& dev = test::test_device();
  const bp_camera cam = test::plate_camera();
  const Eigen::Isometry3d pose = test::plate_pose();
  const PlaneSearchModel sm = plate_search_model(dev);
  const PointImage image = test::plate_over_plane(cam, pose, true);
  const ocl::Buffer<float> points(dev, std::span<const float>(image.xyzw));
  const ocl::Buffer<float> depth = point_depths(dev, points, cam);
  const double deg = std::numbers::pi / 180;
  const std::vector<Eigen::Isometry3d> first = {in_plane_pose(pose, sm.axis, sm.centre, 25 * deg, 9, -6),
                                                pose};
  std::vector<Eigen::Isometry3d> both = first;
  both.push_back(in_plane_pose(pose, sm.axis, sm.centre, -40 * deg, -5, 7));
  const std::vector<PlaneSearchResult> all = plane_search(dev, depth, cam, sm, both, 18.0, 4.8f);
  const auto expect_equal = [&](const std::vector<PlaneSearchResult>& got, const char* what) {
    ASSERT_EQ(got.size(), all.size()) << what;
    for (std::size_t k = 0; k < got.size(); ++k) {
      EXPECT_EQ(got[k].score, all[k].score) << what << " " << k;
      EXPECT_EQ(got[k].start_score, all[k].start_score) << what << " " << k;
      EXPECT_TRUE(got[k].pose.matrix() == all[k].pose.matrix()) << what << " " << k;
    }
  };
  PlaneSearchMemo memo;
  EXPECT_EQ(plane_search(memo, dev, depth, cam, sm, first, 18.0, 4.8f).size(), 2u);
  ASSERT_EQ(memo.starts.size(), 2u);
  // A planted result shows which entries were reused: the held starts, not the new one.
  memo.found[1].score = 123.0f;
  std::vector<PlaneSearchResult> got = plane_search(memo, dev, depth, cam, sm, both, 18.0, 4.8f);
  EXPECT_EQ(got[1].score, 123.0f);
  got[1].score = all[1].score;
  expect_equal(got, "second round");
  EXPECT_EQ(memo.starts.size(), 3u);
  // The first start changed: nothing after it is trusted.
  PlaneSearchMemo stale;
  stale.starts = {both[1], both[0]};
  stale.found = {all[1], all[0]};
  stale.found[0].score = stale.found[1].score = 123.0f;
  expect_equal(plane_search(stale, dev, depth, cam, sm, both, 18.0, 4.8f), "stale memo");
}

// Noisy depth (search_reads_lowpass): on the plate over a plane one thickness beneath, with
// depth noise of one thickness more (sigma 1.5 mm along the rays) the step at the edges drowns
// and the search from a start 11 mm and 25 degrees off goes astray on most seeds; on the points
// moved to their low-passed depth, over the box the detector takes for this camera (margin 3 mm,
// a pixel 1 mm wide at 500 mm: 5 x 5 pixels), it comes back on every seed.
TEST(PlaneSearch, LowPassedDepthFindsThePlateUnderNoise) {
  auto& dev = test::test_device();
  const bp_camera cam = test::plate_camera();
  const Eigen::Isometry3d pose = test::plate_pose();
  const PlaneSearchModel sm = plate_search_model(dev);
  const PpfModel& model = plate_model();
  const double margin = kEdgeMarginVoxels * model.voxel_size / kProbeVoxelDivisor;
  const int radius = search_lowpass_radius(margin, pose.translation().z() / cam.fx);
  ASSERT_EQ(radius, 2);
  const Eigen::Isometry3d start =
      in_plane_pose(pose, sm.axis, sm.centre, 25 * std::numbers::pi / 180, 9, -6);
  const auto found_again = [&](const std::vector<float>& xyzw) {
    const ocl::Buffer<float> points(dev, std::span<const float>(xyzw));
    const std::vector<PlaneSearchResult> found =
        plane_search(dev, point_depths(dev, points, cam), cam, sm, {start}, 18.0, 4.8f);
    return (found[0].pose * sm.centre - pose * sm.centre).norm() < 5.0 &&
           angle_between(found[0].pose.linear(), pose.linear()) * 180 / std::numbers::pi < 3.0;
  };
  int raw = 0, low_passed = 0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    PointImage image = test::plate_over_plane(cam, pose, false);
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 1.5f);
    for (std::size_t i = 0; i < image.xyzw.size() / 4; ++i) {
      float* p = &image.xyzw[4 * i];
      if (p[3] == 0.0f) continue;
      const float s = (p[2] + noise(rng)) / p[2];
      p[0] *= s, p[1] *= s, p[2] *= s;
    }
    raw += found_again(image.xyzw);
    low_passed +=
        found_again(lowpass_points_reference(image.xyzw, lowpass_depth_reference(image, radius)));
  }
  EXPECT_LE(raw, 2);  // the premise: the raw depth is too noisy
  EXPECT_EQ(low_passed, 5);
  // The rule and the box: on at half the thickness; a pixel as wide as the margin, no box.
  EXPECT_TRUE(search_reads_lowpass(0.8, 1.5));
  EXPECT_FALSE(search_reads_lowpass(0.7, 1.5));
  EXPECT_EQ(search_lowpass_radius(3.0, 3.0), 0);
  EXPECT_EQ(search_lowpass_radius(3.0, 2.9), 1);
  EXPECT_EQ(search_lowpass_radius(3.0, 0.0), 0);
  EXPECT_EQ(search_lowpass_radius(1000.0, 1.0), 64);
}
