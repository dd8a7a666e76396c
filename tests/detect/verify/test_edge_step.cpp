// The edge step of verification (host/detect/verify/edge_step.hpp): its arithmetic, and on an image of
// the built-in plate lying on a plane one sheet thickness beneath it (a plate on a plate), the
// right pose against the same plate shifted 20 mm across, in its plane: both lie on surface nearly
// everywhere and score alike; beyond the right pose's edges the sensor sees the step down to
// the plane, beyond the shifted pose's edges on one side it sees the plate run on, and the edge
// step keeps the right pose's lead. And a plate pose laid on a larger flat face seen obliquely
// (a robot arm's): the probes continuing its faces see the face run on, those continuing its rims
// see it a margin behind them, which is why only the face probes are tested.
#include <gtest/gtest.h>

#include <span>

#include "host/detect/verify/verify_poses.hpp"
#include "host/detect/verify/edge_step.hpp"
#include "host/train/edge_probes.hpp"
#include "host/train/ppf_model.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "tests/support/plate_scene.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;

TEST(EdgeStep, StepIsTheMeanPlusTwoStandardErrors) {
  ProbeEvidence e;
  e.mean = 1.5, e.standard_error = 0.25, e.n = 100;
  EXPECT_DOUBLE_EQ(edge_step(e), 2.0);
  e.missing = 400;  // no depth beyond the edges says nothing: the step is that of the 100
  EXPECT_DOUBLE_EQ(edge_step(e), 2.0);
  e.mean = -1.0;
  EXPECT_DOUBLE_EQ(edge_step(e), 0.0);  // never negative
  EXPECT_DOUBLE_EQ(edge_factor(2.0, 1.0, 4.0), 0.5);
  EXPECT_DOUBLE_EQ(edge_factor(2.0, 0.5, 4.0), 1.0);
  EXPECT_DOUBLE_EQ(edge_factor(8.0, 1.0, 4.0), 1.0);  // at most 1
  EXPECT_DOUBLE_EQ(edge_factor(0.0, 1.0, 4.0), 0.0);
  EXPECT_DOUBLE_EQ(edge_factor(-1.0, 1.0, 4.0), 0.0);
  EXPECT_DOUBLE_EQ(edge_factor(0.0, 0.0, 4.0), 1.0);  // off
  EXPECT_DOUBLE_EQ(edge_factor(0.0, 1.0, 0.0), 1.0);  // no gate: untested
}

namespace {

// The model's face probes, as detection takes them (with_rims: all its edge probes).
PointCloud tested_probes(const PpfModel& model, bool with_rims = false) {
  return with_rims ? model.edge_probes : face_probes(model.edge_probes, model.edge_probe_rim);
}

// The pose at `pose` on `image`, verified (no refinement steps), then edge-tested with the face
// probes (with_rims: all edge probes).
VerifiedPose edge_tested(const PpfModel& model, const PointImage& image,
                        const Eigen::Isometry3d& pose, bool with_rims) {
  auto& dev = test::test_device();
  const bp_camera cam = test::plate_camera();
  const FitGeometry g = test::plate_fit_geometry(model);
  const ocl::Buffer<float> points(dev, std::span<const float>(image.xyzw));
  ProbeModel tm;
  tm.fit_points = static_cast<std::uint32_t>(model.fit_cloud.points.size());
  tm.probes = tested_probes(model, with_rims);
  tm.lookalikes = 0;
  tm.probe_lookalike.assign(tm.probes.points.size(), 0);
  tm.edge_probes = static_cast<std::uint32_t>(tm.probes.points.size());
  PointCloud all = model.fit_cloud;
  append_cloud(all, tm.probes);
  const DeviceFitModel fit = upload_fit_model(dev, model.fit_cloud);
  const DeviceFitModel with_probes = upload_fit_model(dev, all);
  VerifyOptions ro;
  ro.refine.iterations = 0;
  ro.noise_factor = 3.5f;
  std::vector<VerifiedPose> refined = refine_and_verify(
      [&](const std::vector<bp_pose_fit>& f) { return pose_fit_sums(dev, points, cam, fit, f); },
      cam, g, fit.size, {{pose.linear(), pose.translation()}}, ro);
  LookalikeHolesOptions to;
  to.edge_scale = 1.0f;
  lookalike_holes([&](const std::vector<bp_pose_fit>& f) {
              return pose_fit_sums(dev, points, cam, with_probes, f);
            },
            cam, g, tm, refined, to);
  return refined[0];
}

void plate_shifted_on_a_plate(bool holes_without_depth) {
  auto& dev = test::test_device();
  const PpfModel model = train_ppf_model(make_builtin_part("plate"), PpfTrainParams{}, nullptr, dev);
  ASSERT_GT(model.edge_face_probes(), 300u);
  const bp_camera cam = test::plate_camera();
  const Eigen::Isometry3d pose = test::plate_pose();
  const PointImage image = test::plate_over_plane(cam, pose, holes_without_depth);
  const Eigen::Matrix3d R = pose.linear();
  const Eigen::Vector3d t = pose.translation();

  const FitGeometry g = test::plate_fit_geometry(model);
  const DeviceFitModel fit = upload_fit_model(dev, model.fit_cloud);
  const ocl::Buffer<float> points(dev, std::span<const float>(image.xyzw));
  // The right pose, and the plate shifted 20 mm across (in its plane, along y): its one long
  // edge lies over the right plate, where the surface runs on.
  const std::vector<PoseToRefine> poses = {{R, t}, {R, t + R * Eigen::Vector3d(0, 20, 0)}};
  VerifyOptions ro;
  ro.refine.iterations = 0;
  ro.noise_factor = 3.5f;
  std::vector<VerifiedPose> refined = refine_and_verify(
      [&](const std::vector<bp_pose_fit>& f) { return pose_fit_sums(dev, points, cam, fit, f); },
      cam, g, fit.size, poses, ro);
  // Without the test the shifted plate keeps most of the right one's score (what costs it
  // some is the right plate's holes under its sheet).
  ASSERT_GT(refined[0].score(), 0.5);
  EXPECT_GT(refined[1].score(), 0.7 * refined[0].score());

  ProbeModel tm;
  tm.fit_points = fit.size;
  tm.probes = tested_probes(model);
  tm.lookalikes = 0;  // edge probes only: their group is the look-alike count
  tm.probe_lookalike.assign(tm.probes.points.size(), 0);
  tm.edge_probes = static_cast<std::uint32_t>(tm.probes.points.size());
  PointCloud all = model.fit_cloud;
  append_cloud(all, tm.probes);
  const DeviceFitModel with_probes = upload_fit_model(dev, all);
  const std::vector<VerifiedPose> before = refined;
  LookalikeHolesOptions to;
  to.edge_scale = 1.0f;
  const auto device = [&](const std::vector<bp_pose_fit>& f) {
    return pose_fit_sums(dev, points, cam, with_probes, f);
  };
  lookalike_holes(device, cam, g, tm, refined, to);
  ASSERT_TRUE(refined[1].evidence.edge_tested);
  EXPECT_FALSE(refined[0].evidence.lookalike_tested);
  const double gate = refined[0].evidence.tolerance;
  if (holes_without_depth) {
    // No depth anywhere beyond the right pose's edges, which says nothing (edge_step.hpp): too
    // few probes with depth, untested. The shifted pose's edge over the right plate sees it run on.
    EXPECT_FALSE(refined[0].evidence.edge_tested);
    EXPECT_LT(refined[1].evidence.edge_step, 0.3 * gate);
  } else {
    // The plane beneath: one thickness (1.5 mm), give or take the noise's standard errors.
    ASSERT_TRUE(refined[0].evidence.edge_tested);
    EXPECT_GT(refined[0].evidence.edge_step, 1.2);
    EXPECT_LT(refined[0].evidence.edge_step, 2.2);
    EXPECT_LT(refined[1].evidence.edge_step, 0.7 * refined[0].evidence.edge_step);
  }
  for (std::size_t k = 0; k < 2; ++k) {
    const double factor = refined[k].evidence.edge_tested ? std::min(1.0, refined[k].evidence.edge_step / gate) : 1.0;
    EXPECT_NEAR(refined[k].score(), before[k].score() * factor, 1e-9) << k;
  }
  EXPECT_LT(refined[1].score(), 0.75 * refined[0].score() * before[1].score() / before[0].score());

  // The C++ reference gives the same steps (the classes are exact, the residuals floats).
  std::vector<VerifiedPose> again = before;
  lookalike_holes([&](const std::vector<bp_pose_fit>& f) {
              return pose_fit_sums_reference(image, cam, all, f);
            },
            cam, g, tm, again, to);
  for (std::size_t k = 0; k < 2; ++k) EXPECT_NEAR(again[k].evidence.edge_step, refined[k].evidence.edge_step, 1e-3) << k;
  // Scale 0, or no edge probes: untouched.
  std::vector<VerifiedPose> off = before;
  to.edge_scale = 0;
  lookalike_holes(device, cam, g, tm, off, to);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(off[k].score(), before[k].score());
    EXPECT_FALSE(off[k].evidence.edge_tested);
  }
  to.edge_scale = 1;
  tm.edge_probes = 0;
  off = before;
  lookalike_holes(device, cam, g, tm, off, to);
  for (std::size_t k = 0; k < 2; ++k) EXPECT_EQ(off[k].score(), before[k].score());
}

}  // namespace

TEST(EdgeStep, ThePlateShiftedOnAPlateLosesToTheRightPose) { plate_shifted_on_a_plate(false); }

TEST(EdgeStep, ThePlateShiftedLosesAlsoWhereNothingBeyondItHasDepth) {
  plate_shifted_on_a_plate(true);
}

// The plate turned 70 degrees from the camera (a robot arm's face in a basket was seen at 72).
TEST(EdgeStep, APoseLaidOnALargerFaceSeenObliquelyShowsNoStepAtItsFaceProbes) {
  const PpfModel model =
      train_ppf_model(make_builtin_part("plate"), PpfTrainParams{}, nullptr, test::test_device());
  ASSERT_GT(model.edge_face_probes(), 300u);
  ASSERT_GT(model.edge_probes.points.size(), model.edge_face_probes());  // the rim probes
  Eigen::Isometry3d pose = test::plate_pose();
  pose.linear() = Eigen::AngleAxisd(70.0 * 3.14159265358979 / 180, Eigen::Vector3d::UnitX()) *
                  pose.linear();
  const bp_camera cam = test::plate_camera();
  const VerifiedPose on_face = edge_tested(model, test::plane_of_plate_face(cam, pose), pose, false);
  const VerifiedPose with_rims =
      edge_tested(model, test::plane_of_plate_face(cam, pose), pose, true);
  const VerifiedPose right =
      edge_tested(model, test::plate_over_plane(cam, pose, false), pose, false);
  ASSERT_TRUE(on_face.evidence.edge_tested && with_rims.evidence.edge_tested && right.evidence.edge_tested);
  const double gate = on_face.evidence.tolerance;
  // The face runs on beyond the pose's edges: no step at the face probes, a false one at the rims.
  EXPECT_LT(on_face.evidence.edge_step, 0.25 * gate);
  EXPECT_GT(with_rims.evidence.edge_step, 2.0 * on_face.evidence.edge_step + 0.1 * gate);
  // The right plate over the plane beneath steps down by a thickness (1.5 mm along its normal,
  // more along the rays).
  EXPECT_GT(right.evidence.edge_step, 1.2);
  EXPECT_GT(right.evidence.edge_step, 3.0 * on_face.evidence.edge_step);
}
