// The look-alike holes of verification (host/detect/verify/lookalike_holes.hpp): the evidence of a look-alike's
// probes from a probe pass's residuals (mean and standard error of the depth excess along the
// rays, the clamp, the infinite residuals of probes beyond the gate, probes that say nothing),
// and, on an image of the built-in plate lying on a surface one sheet thickness below it (a
// plate on a plate), the right pose and its three turned look-alikes: every other score term
// finds them alike, the look-alike holes cost the look-alikes and leave the right pose alone.
#include <gtest/gtest.h>

#include <cmath>
#include <span>

#include "host/detect/verify/verify_poses.hpp"
#include "host/detect/verify/lookalike_holes.hpp"
#include "host/train/ppf_model.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "tests/support/plate_scene.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;

namespace {

// n probes of look-alike 0 on a plane facing the camera 500 mm ahead (so the cosine is 1).
PointCloud facing_probes(std::size_t n) {
  PointCloud c;
  for (std::size_t i = 0; i < n; ++i) {
    c.points.emplace_back(float(i % 10), float(i / 10), 0.0f);
    c.normals.emplace_back(0.0f, 0.0f, -1.0f);
  }
  return c;
}

const Eigen::Vector3d kAhead(0, 0, 500);

}  // namespace

TEST(LookalikeHoles, EvidenceIsTheMeanDepthExcessAlongTheRays) {
  const PointCloud probes = facing_probes(4);
  const std::vector<std::uint32_t> twin = {0, 0, 0, 1};
  const std::vector<std::uint8_t> cls(4, BP_FIT_INLIER);
  // r = n . (p - q): -1.5 where the sensor saw 1.5 mm farther (facing the camera: the excess).
  const std::vector<float> r = {-1.0f, -2.0f, -3.0f, -100.0f};
  const ProbeEvidence e =
      probe_evidence(r, cls, Eigen::Matrix3d::Identity(), kAhead, probes, twin, 0, 10.0);
  ASSERT_EQ(e.n, 3u);  // the fourth probe is another look-alike's
  EXPECT_EQ(e.missing, 0u);
  EXPECT_NEAR(e.mean, 2.0, 1e-5);
  EXPECT_NEAR(e.standard_error, 1.0 / std::sqrt(3.0), 1e-5);  // sample sd 1
  EXPECT_NEAR(holes_excess(e, 3, 0.0, 10.0), 2.0 - 2.0 / std::sqrt(3.0), 1e-5);
  // The pose's own share m of points without depth comes off in the gate's units, and the
  // spread of one draw of it, sqrt(m (1 - m)) gates, joins the standard error.
  EXPECT_NEAR(holes_excess(e, 3, 0.001, 10.0),
              2.0 - 0.01 - 2.0 * std::sqrt(1.0 / 3.0 + 0.001 * 0.999 * 100.0), 1e-5);
  EXPECT_EQ(holes_excess(e, 3, 0.05, 10.0), 0.0);
  EXPECT_EQ(holes_excess(e, 3, 0.5, 10.0), 0.0);
  EXPECT_EQ(holes_excess(e, 4, 0.0, 10.0), 0.0);  // too few probes: untested
}

// The case that made the spread term (lookalike_holes.hpp): a look-alike's probes all in one patch of
// lost depth, 26 of 28 without depth, at a pose that misses 44 % of its own points.
TEST(LookalikeHoles, OnePatchWithoutDepthIsOneDrawOfThePosesOwnMissingShare) {
  ProbeEvidence e;
  e.n = 28;
  e.missing = 26;
  const double gate = 6.0;
  e.mean = 26.0 * gate / 28.0;  // the two probes with depth on the surface (excess 0)
  e.standard_error = gate * std::sqrt(26.0 * 2.0 / (28.0 * 27.0)) / std::sqrt(28.0);
  EXPECT_EQ(holes_excess(e, 10, 0.44, gate), 0.0);
  // The same probes at a pose that has depth nearly everywhere else: a look-alike's holes
  // whose bottoms the projector cannot light, still evidence.
  EXPECT_GT(holes_excess(e, 10, 0.02, gate), 0.5 * gate);
  EXPECT_NEAR(holes_excess(e, 10, 0.0, gate), e.mean - 2.0 * e.standard_error, 1e-9);
}

// The probes with depth alone (lookalike_holes.hpp): where the pose's own share without depth is
// half, the spread of that share outweighs every mean, and only they still tell.
TEST(LookalikeHoles, ProbesWithDepthTellAlsoWhereHalfThePosesPointsHaveNone) {
  const double gate = 6.0;
  ProbeEvidence all;  // 30 probes: 15 without depth (as the gate), 15 seen through to the gate
  all.n = 30;
  all.missing = 15;
  all.mean = gate;
  ProbeEvidence seen;  // the 15 with depth
  seen.n = 15;
  seen.mean = gate;
  EXPECT_EQ(holes_excess(all, 10, 0.5, gate), 0.0);
  EXPECT_DOUBLE_EQ(seen_excess(seen, 10), gate);
  seen.mean = 1.5;  // the sheet beneath, 1.5 mm deeper, less two standard errors
  seen.standard_error = 0.2;
  EXPECT_NEAR(seen_excess(seen, 10), 1.1, 1e-12);
  // The right pose's probes with depth lie on its own surface; fewer than min_probes say nothing.
  seen.mean = -0.3;
  EXPECT_EQ(seen_excess(seen, 10), 0.0);
  seen.mean = gate;
  seen.n = 9;
  EXPECT_EQ(seen_excess(seen, 10), 0.0);
  EXPECT_EQ(seen_excess(ProbeEvidence{}, 0), 0.0);
}

TEST(LookalikeHoles, SeenThroughAndNoDepthCountAsTheGateInFrontAndHiddenSayNothing) {
  const PointCloud probes = facing_probes(7);
  const std::vector<std::uint32_t> twin(7, 0);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // Seen through beyond the gate, something in front beyond it, no depth, hidden, and finite
  // residuals past the clamp on either side and at 0.
  const std::vector<std::uint8_t> cls = {BP_FIT_SEE_THROUGH, BP_FIT_OCCLUDED, BP_FIT_MISSING,
                                         BP_FIT_HIDDEN,      BP_FIT_SEE_THROUGH, BP_FIT_OCCLUDED,
                                         BP_FIT_INLIER};
  const std::vector<float> r = {nan, nan, nan, nan, -50.0f, 50.0f, 0.0f};
  const ProbeEvidence e = probe_evidence(r, cls, Eigen::Matrix3d::Identity(), kAhead, probes, twin, 0, 5.0);
  ASSERT_EQ(e.n, 5u);
  EXPECT_EQ(e.missing, 1u);
  EXPECT_NEAR(e.mean, (5.0 + 5.0 + 5.0 - 5.0 + 0.0) / 5.0, 1e-9);
  // The edge step's reading: no depth says nothing, and is still counted as missing.
  const ProbeEvidence neutral = probe_evidence(r, cls, Eigen::Matrix3d::Identity(), kAhead, probes,
                                             twin, 0, 5.0, NoDepth::neutral);
  ASSERT_EQ(neutral.n, 4u);
  EXPECT_EQ(neutral.missing, 1u);
  EXPECT_NEAR(neutral.mean, (5.0 + 5.0 - 5.0 + 0.0) / 4.0, 1e-9);
  // A probe without depth seen obliquely (70 degrees) says nothing: such surfaces often give
  // none on real material.
  PointCloud oblique = facing_probes(1);
  oblique.normals[0] = {0.0f, std::sin(1.22f), -std::cos(1.22f)};
  EXPECT_EQ(probe_evidence(std::vector<float>{nan}, std::vector<std::uint8_t>{BP_FIT_MISSING},
                          Eigen::Matrix3d::Identity(), kAhead, oblique,
                          std::vector<std::uint32_t>{0}, 0, 5.0)
                .n,
            0u);
  // A probe facing away from the camera gives no distance along its ray.
  PointCloud away = facing_probes(1);
  away.normals[0] = {0.0f, 0.0f, 1.0f};
  EXPECT_EQ(probe_evidence(std::vector<float>{-1.0f}, std::vector<std::uint8_t>{BP_FIT_INLIER},
                          Eigen::Matrix3d::Identity(), kAhead, away, std::vector<std::uint32_t>{0},
                          0, 5.0)
                .n,
            0u);
  // No probe: nothing, and the test is off.
  const ProbeEvidence none =
      probe_evidence({}, {}, Eigen::Matrix3d::Identity(), kAhead, PointCloud{}, {}, 0, 5.0);
  EXPECT_EQ(none.n, 0u);
  EXPECT_EQ(holes_excess(none, 1, 0.0, 5.0), 0.0);
  // One residual and class per probe, or a logic error.
  EXPECT_THROW(probe_evidence(std::vector<float>{0.0f}, cls, Eigen::Matrix3d::Identity(), kAhead,
                             probes, twin, 0, 5.0),
               std::logic_error);
}

namespace {

enum class Dropout {
  none,     // the plate beneath seen through every hole
  holes,    // no depth wherever the plate is not: a projector that cannot light a hole's bottom
  patches,  // no depth in every other 12 x 12 pixel square, on the plate and beneath alike
};

// The plate's right pose and its three look-alikes (turned over) against an image of the plate
// over its own plane one thickness (1.5 mm) farther along its normal, where the plate beneath
// lies, with depth missing as `dropout` says.
void plate_and_its_look_alikes(Dropout dropout) {
  auto& dev = test::test_device();
  const PpfModel model = train_ppf_model(make_builtin_part("plate"), PpfTrainParams{}, nullptr, dev);
  ASSERT_EQ(model.lookalikes.size(), 3u);
  const bp_camera cam = test::plate_camera();
  const Eigen::Isometry3d pose = test::plate_pose();
  const Eigen::Matrix3d R = pose.linear();
  const Eigen::Vector3d t = pose.translation();
  PointImage image = test::plate_over_plane(cam, pose, dropout == Dropout::holes);
  if (dropout == Dropout::patches) image = test::without_depth_in_patches(std::move(image), 12);

  const FitGeometry g = test::plate_fit_geometry(model);
  const DeviceFitModel fit = upload_fit_model(dev, model.fit_cloud);
  const ocl::Buffer<float> points(dev, std::span<const float>(image.xyzw));
  std::vector<PoseToRefine> poses = {{R, t}};
  for (const Eigen::Isometry3d& S : model.lookalikes)
    poses.push_back({R * S.linear(), R * S.translation() + t});
  VerifyOptions ro;
  ro.refine.iterations = 0;  // the poses as given: the look-alikes lie exactly on the outline
  ro.noise_factor = 3.5f;
  std::vector<VerifiedPose> refined = refine_and_verify(
      [&](const std::vector<bp_pose_fit>& f) { return pose_fit_sums(dev, points, cam, fit, f); },
      cam, g, fit.size, poses, ro);
  // Without the test the look-alikes score within a few hundredths of the right pose.
  for (std::size_t k = 1; k < refined.size(); ++k)
    EXPECT_GT(refined[k].score(), refined[0].score() - 0.05) << k;

  ProbeModel tm;
  tm.fit_points = fit.size;
  tm.probes = model.lookalike_probes;
  tm.probe_lookalike = model.probe_lookalike;
  tm.lookalikes = 3;
  PointCloud both = model.fit_cloud;
  append_cloud(both, tm.probes);
  const DeviceFitModel with_probes = upload_fit_model(dev, both);
  const std::vector<VerifiedPose> before = refined;
  LookalikeHolesOptions to;
  to.band_ratio = 0.005f;
  lookalike_holes(
      [&](const std::vector<bp_pose_fit>& f) {
        return pose_fit_sums(dev, points, cam, with_probes, f);
      },
      cam, g, tm, refined, to);
  const double band = 0.005 * model.diameter;
  if (dropout == Dropout::patches) {
    // Half of every pose's points without depth: the share's spread alone is a gate.
    for (const VerifiedPose& r : refined)
      EXPECT_GT(double(r.evidence.missing) / double(r.evidence.visible), 0.3) << r.evidence.missing << " of " << r.evidence.visible;
  }
  ASSERT_TRUE(refined[0].evidence.lookalike_tested);
  EXPECT_LT(refined[0].evidence.lookalike_excess, band);
  EXPECT_DOUBLE_EQ(refined[0].score(), before[0].score());
  for (std::size_t k = 1; k < refined.size(); ++k) {
    ASSERT_TRUE(refined[k].evidence.lookalike_tested) << k;
    // The sheet beneath: about its thickness deeper, less the standard errors; no depth: as
    // far as the gate, less the look-alike's own share of points without depth.
    EXPECT_GT(refined[k].evidence.lookalike_excess, 1.0) << k;
    if (dropout != Dropout::holes) {
      EXPECT_LT(refined[k].evidence.lookalike_excess, 1.6) << k;
    }
    EXPECT_NEAR(refined[k].score(), before[k].score() * band / refined[k].evidence.lookalike_excess, 1e-6) << k;
    EXPECT_LT(refined[k].score(), 0.8 * refined[0].score()) << k;
  }
  // The same pass with the C++ reference gives the same excesses (the classes are exact).
  std::vector<VerifiedPose> again = before;
  lookalike_holes(
      [&](const std::vector<bp_pose_fit>& f) {
        return pose_fit_sums_reference(image, cam, both, f);
      },
      cam, g, tm, again, to);
  for (std::size_t k = 0; k < again.size(); ++k)
    EXPECT_NEAR(again[k].evidence.lookalike_excess, refined[k].evidence.lookalike_excess, 1e-3) << k;
  // Band 0, or no probes: the scores are untouched.
  std::vector<VerifiedPose> off = before;
  to.band_ratio = 0;
  lookalike_holes([&](const std::vector<bp_pose_fit>& f) { return pose_fit_sums(dev, points, cam, with_probes, f); },
            cam, g, tm, off, to);
  for (std::size_t k = 0; k < off.size(); ++k) EXPECT_EQ(off[k].score(), before[k].score());
}

}  // namespace

TEST(LookalikeHoles, ThePlateTurnedOverLosesToTheRightPoseOnAPlateBeneath) {
  plate_and_its_look_alikes(Dropout::none);
}

TEST(LookalikeHoles, ThePlateTurnedOverLosesToTheRightPoseOverHolesWithoutDepth) {
  plate_and_its_look_alikes(Dropout::holes);
}

// Fails with the share without depth alone: every look-alike's excess is 0 there.
TEST(LookalikeHoles, ThePlateTurnedOverLosesToTheRightPoseWhereDepthIsLostInPatches) {
  plate_and_its_look_alikes(Dropout::patches);
}
