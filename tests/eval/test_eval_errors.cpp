// Pose errors, matching and precision of `binpick eval` against hand-made cases with known
// answers (paper section III-D; symmetries in the BOP models_info.json convention).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "host/formats/bop/models_info.hpp"
#include "host/core/error.hpp"
#include "host/eval/metrics/evaluate.hpp"
#include "host/eval/metrics/pose_error.hpp"
#include "host/eval/metrics/precision_curves.hpp"

namespace binpick::eval {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Eigen::Matrix3d rot(double deg, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(deg * kDeg, axis.normalized()).toRotationMatrix();
}

const Eigen::Matrix3d kGtR = rot(37, {0.3, -1, 0.5});
const Eigen::Vector3d kGtT{12, -40, 830};

PartSymmetries bolt_axis_z(Eigen::Vector3d offset = Eigen::Vector3d::Zero()) {
  return {{{Eigen::Vector3d::UnitZ(), offset}}, {}};
}

TEST(PoseError, IdentityHasNoError) {
  const auto e = symmetric_pose_error(kGtR, kGtT, kGtR, kGtT, {});
  EXPECT_NEAR(e.rotation_deg, 0, 1e-6);
  EXPECT_NEAR(e.translation_mm, 0, 1e-9);
}

TEST(PoseError, KnownRotationGivesItsAngle) {
  for (const Eigen::Vector3d& axis : {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0, 0, 1),
                                     Eigen::Vector3d(-1, 0.2, 0)}) {
    // The same 30 degrees whether applied in the model frame or in the camera frame.
    EXPECT_NEAR(symmetric_pose_error(kGtR, kGtT, kGtR * rot(30, axis), kGtT, {}).rotation_deg, 30, 1e-9);
    EXPECT_NEAR(symmetric_pose_error(kGtR, kGtT, rot(30, axis) * kGtR, kGtT, {}).rotation_deg, 30, 1e-9);
  }
  EXPECT_NEAR(rotation_angle_deg(Eigen::Matrix3d::Identity(), rot(179.9, {1, 1, 0})), 179.9, 1e-5);
  EXPECT_NEAR(rotation_angle_deg(Eigen::Matrix3d::Identity(), rot(180, {0, 1, 0})), 180, 1e-6);
  EXPECT_NEAR(rotation_angle_deg(Eigen::Matrix3d::Identity(), rot(0.001, {0, 1, 0})), 0.001, 1e-9);
}

TEST(PoseError, TranslationIsTheDistance) {
  const Eigen::Vector3d off = Eigen::Vector3d(3, 4, 12).normalized() * 5.2;
  EXPECT_NEAR(symmetric_pose_error(kGtR, kGtT, kGtR, kGtT + off, {}).translation_mm, 5.2, 1e-9);
}

TEST(PoseError, RotationAboutAContinuousAxisIsNoError) {
  for (double a : {0.0, 10.0, 77.0, 180.0, 295.0}) {
    const auto e = symmetric_pose_error(kGtR, kGtT, kGtR * rot(a, {0, 0, 1}), kGtT, bolt_axis_z());
    EXPECT_NEAR(e.rotation_deg, 0, 1e-6) << a;
    EXPECT_NEAR(e.translation_mm, 0, 1e-9) << a;
  }
  // Tilting the axis by 20 degrees is an error of 20 degrees, whatever the spin about it.
  const auto e = symmetric_pose_error(kGtR, kGtT, kGtR * rot(20, {1, 0, 0}) * rot(130, {0, 0, 1}),
                                      kGtT, bolt_axis_z());
  EXPECT_NEAR(e.rotation_deg, 20, 1e-6);
}

TEST(PoseError, ContinuousAxisThroughAnOffsetMovesTheTranslation) {
  // The part turns about a vertical axis through (10, 0, 0) of its frame: the pose turned about
  // that axis has another translation but is the same part in the same place.
  const Eigen::Vector3d o(10, 0, 0);
  const Eigen::Matrix3d C = rot(90, {0, 0, 1});
  const Eigen::Vector3d t_est = kGtR * (o - C * o) + kGtT;
  const auto e = symmetric_pose_error(kGtR, kGtT, kGtR * C, t_est, bolt_axis_z(o));
  EXPECT_NEAR(e.rotation_deg, 0, 1e-6);
  EXPECT_NEAR(e.translation_mm, 0, 1e-6);
  // Without the symmetry that is 90 degrees and |o - C o| = 10 sqrt 2 mm away.
  const auto plain = symmetric_pose_error(kGtR, kGtT, kGtR * C, t_est, {});
  EXPECT_NEAR(plain.rotation_deg, 90, 1e-6);
  EXPECT_NEAR(plain.translation_mm, 10 * std::sqrt(2.0), 1e-6);
}

TEST(PoseError, DiscreteHalfTurnSymmetry) {
  PartSymmetries flip;
  Eigen::Matrix4d D = Eigen::Matrix4d::Identity();
  D.topLeftCorner<3, 3>() = rot(180, {1, 0, 0});
  flip.discrete.push_back(D);
  EXPECT_NEAR(symmetric_pose_error(kGtR, kGtT, kGtR * rot(180, {1, 0, 0}), kGtT, flip).rotation_deg, 0, 1e-6);
  EXPECT_NEAR(symmetric_pose_error(kGtR, kGtT, kGtR * rot(170, {1, 0, 0}), kGtT, flip).rotation_deg, 10, 1e-6);
  EXPECT_NEAR(symmetric_pose_error(kGtR, kGtT, kGtR * rot(10, {1, 0, 0}), kGtT, flip).rotation_deg, 10, 1e-6);
  // A half turn about another axis is not a symmetry.
  EXPECT_NEAR(symmetric_pose_error(kGtR, kGtT, kGtR * rot(180, {0, 1, 0}), kGtT, flip).rotation_deg, 180, 1e-6);

  // A flip whose axis does not pass through the origin carries a translation: T_gt * D is right.
  D.topRightCorner<3, 1>() = Eigen::Vector3d(0, 0, 20);
  flip.discrete = {D};
  const Eigen::Vector3d t_est = kGtR * D.topRightCorner<3, 1>() + kGtT;
  const auto e = symmetric_pose_error(kGtR, kGtT, kGtR * D.topLeftCorner<3, 3>(), t_est, flip);
  EXPECT_NEAR(e.rotation_deg, 0, 1e-6);
  EXPECT_NEAR(e.translation_mm, 0, 1e-9);
}

TEST(PoseError, TwoAxesMakeEveryRotationRight) {
  PartSymmetries sphere{{{Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()},
                         {Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero()}}, {}};
  EXPECT_EQ(symmetric_pose_error(kGtR, kGtT, rot(100, {1, 2, 3}), kGtT, sphere).rotation_deg, 0);
}

TEST(PoseError, ClosedFormBestAngleMatchesFineSampling) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const Eigen::Matrix3d M = rot(180 * (u(rng) + 1) / 2, {u(rng), u(rng), u(rng) + 1e-3});
    double sampled = 1e9;
    for (int i = 0; i < 36000; ++i)
      sampled = std::min(sampled, rotation_angle_deg(rot(i * 0.01, axis), M));
    const double theta = best_angle_about_axis(M, axis);
    const double closed = rotation_angle_deg(Eigen::AngleAxisd(theta, axis).toRotationMatrix(), M);
    EXPECT_LE(closed, sampled + 1e-9) << trial;
    EXPECT_NEAR(closed, sampled, 0.01) << trial;
  }
}

// A dataset in memory: one image with two parts of a 52 mm object 100 mm apart.
Dataset two_part_dataset(PartSymmetries symmetries = {}) {
  Dataset d;
  d.root = "/nowhere";
  d.label = "hand-made";
  d.models[1] = {52.0, symmetries};
  EvalImage image;
  image.gt.push_back({1, {kGtR, kGtT}});
  image.gt.push_back({1, {rot(90, {0, 1, 0}), kGtT + Eigen::Vector3d(100, 0, 0)}});
  d.images[{0, 0}] = image;
  d.images[{1, 0}] = image;
  return d;
}

bop::ResultRow row(int scene, double score, const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                   double time = 0.5) {
  bop::ResultRow r;
  r.scene_id = scene, r.score = score, r.R = R, r.t = t, r.time = time;
  return r;
}

TEST(Evaluate, MatchesTheNearestPartAndMeasuresItsErrors) {
  const Dataset d = two_part_dataset();
  const Eigen::Vector3d second_t = kGtT + Eigen::Vector3d(100, 0, 0);
  const std::vector<bop::ResultRow> rows{
      row(0, 50, rot(90, {0, 1, 0}) * rot(12, {1, 0, 0}), second_t + Eigen::Vector3d(0, 5.2, 0)),
      row(0, 80, kGtR, kGtT + Eigen::Vector3d(0, 0, 2.6)),
  };
  const EvalSummary s = evaluate(d, rows);
  ASSERT_EQ(s.results.size(), 2u);
  EXPECT_EQ(s.results[0].gt_index, 1);
  EXPECT_NEAR(s.results[0].translation_pct, 10.0, 1e-9);
  EXPECT_NEAR(s.results[0].rotation_deg, 12.0, 1e-6);
  EXPECT_EQ(s.results[1].gt_index, 0);
  EXPECT_NEAR(s.results[1].translation_pct, 5.0, 1e-9);
  // The top-voted one is the higher score, not the first row.
  EXPECT_FALSE(s.results[0].top);
  EXPECT_TRUE(s.results[1].top);
  EXPECT_EQ(s.results[1].rank, 1);
  // 0.5 s for the image's two hypotheses.
  EXPECT_NEAR(s.ms_per_hypothesis, 250, 1e-9);
  EXPECT_NEAR(s.results[0].ms, 250, 1e-9);
  EXPECT_EQ(s.images, 2u);
  EXPECT_EQ(s.images_with_results, 1u);
  // At (10 %, 15 deg) both are right; at (5 %, 5 deg) only the top one.
  EXPECT_DOUBLE_EQ(s.loose.all, 1.0);
  EXPECT_DOUBLE_EQ(s.strict.all, 0.5);
  EXPECT_DOUBLE_EQ(s.strict.top, 1.0);
  EXPECT_NEAR(s.median_translation_pct_all, 7.5, 1e-9);
}

TEST(Evaluate, SymmetricPartAndUnmatchedObject) {
  Dataset d = two_part_dataset(bolt_axis_z());
  d.models[2] = {30.0, {}};
  const std::vector<bop::ResultRow> rows{
      row(1, 10, kGtR * rot(123, {0, 0, 1}), kGtT),
      [] { auto r = row(1, 5, kGtR, kGtT); r.obj_id = 2; return r; }(),  // no part 2 in the image
  };
  const EvalSummary s = evaluate(d, rows);
  EXPECT_NEAR(s.results[0].rotation_deg, 0, 1e-6);
  EXPECT_EQ(s.results[1].gt_index, -1);
  EXPECT_TRUE(std::isinf(s.results[1].rotation_deg));
  EXPECT_EQ(s.unmatched, 1u);
  EXPECT_DOUBLE_EQ(s.loose.all, 0.5);
  EXPECT_DOUBLE_EQ(s.loose.top, 1.0);
}

// A nut 16 mm tall with its origin on its bottom face, turned over about an axis through its
// middle (a symmetry: x -> (x, -y, 16 - z)). Detected turned over, its origin lies 16 mm from
// its own and 14 mm from a neighbour's: it is matched to its own and is right.
TEST(Evaluate, MatchesThroughASymmetryAwayFromTheOrigin) {
  Eigen::Matrix4d flip = Eigen::Matrix4d::Identity();
  flip.topLeftCorner<3, 3>() = rot(180, {1, 0, 0});
  flip(2, 3) = 16.0;
  Dataset d;
  d.root = "/nowhere";
  d.label = "nuts";
  d.models[1] = {38.0, {{}, {flip}}};
  EvalImage image;
  const Eigen::Matrix3d R = rot(20, {1, 1, 0});
  const Eigen::Vector3d t{5, 7, 900};
  const Eigen::Vector3d flipped_t = R * Eigen::Vector3d(0, 0, 16) + t;
  image.gt.push_back({1, {rot(75, {0, 1, 1}), flipped_t + Eigen::Vector3d(14, 0, 0)}});
  image.gt.push_back({1, {R, t}});
  d.images[{0, 0}] = image;
  const std::vector<bop::ResultRow> rows{row(0, 1, R * rot(180, {1, 0, 0}), flipped_t)};
  const EvalSummary s = evaluate(d, rows);
  ASSERT_EQ(s.results.size(), 1u);
  EXPECT_EQ(s.results[0].gt_index, 1);
  EXPECT_NEAR(s.results[0].translation_mm, 0, 1e-9);
  EXPECT_NEAR(s.results[0].rotation_deg, 0, 1e-6);
  EXPECT_DOUBLE_EQ(s.loose.top, 1.0);
}

TEST(Evaluate, PerObjectFiguresRankEachObjectsRowsAlone) {
  Dataset d = two_part_dataset();
  d.models[2] = {30.0, {}};
  for (auto& [key, image] : d.images) image.gt[1].obj_id = 2;  // the second part is object 2
  const Eigen::Vector3d second_t = kGtT + Eigen::Vector3d(100, 0, 0);
  const auto of_two = [](bop::ResultRow r) { r.obj_id = 2; return r; };
  const std::vector<bop::ResultRow> rows{
      row(0, 0.9, kGtR, kGtT),                                     // object 1, right
      of_two(row(0, 0.5, rot(90, {0, 1, 0}), second_t)),           // object 2, right
      of_two(row(0, 0.4, kGtR, second_t + Eigen::Vector3d(0, 0, 20))),  // object 2, wrong
      row(1, 0.3, kGtR, kGtT + Eigen::Vector3d(0, 0, 40)),        // object 1, wrong
  };
  const EvalSummary all = evaluate(d, rows);
  EXPECT_DOUBLE_EQ(all.loose.top, 0.5);  // over all: each image's best row, whatever its object
  EXPECT_DOUBLE_EQ(all.loose.all, 0.5);
  const auto objects = per_object(d, all);
  ASSERT_EQ(objects.size(), 2u);
  const EvalSummary& one = objects[0].summary;
  const EvalSummary& two = objects[1].summary;
  EXPECT_EQ(objects[0].obj_id, 1);
  EXPECT_EQ(objects[1].obj_id, 2);
  EXPECT_EQ(one.hypotheses, 2u);
  EXPECT_EQ(two.hypotheses, 2u);
  EXPECT_EQ(one.images, 2u);
  EXPECT_EQ(two.images_with_results, 1u);
  EXPECT_DOUBLE_EQ(one.loose.top, 0.5);
  EXPECT_DOUBLE_EQ(two.loose.top, 1.0);  // its own best row of image 0, below object 1's
  EXPECT_DOUBLE_EQ(two.loose.all, 0.5);
  EXPECT_NEAR(two.ms_per_hypothesis, 500.0 / 3, 1e-9);  // image 0's 0.5 s over its 3 rows
  EXPECT_NEAR(one.ms_per_hypothesis, (500.0 / 3 + 500.0) / 2, 1e-9);
  EXPECT_TRUE(one.results.empty());
  // One object: no per-object figures.
  EXPECT_TRUE(per_object(d, evaluate(d, {rows[0], rows[3]})).empty());
}

TEST(Evaluate, RowsOutsideTheDatasetAreInputErrors) {
  const Dataset d = two_part_dataset();
  try {
    evaluate(d, {row(0, 1, kGtR, kGtT), row(7, 1, kGtR, kGtT)});
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("row 2 is for scene 7 image 0"), std::string::npos) << e.what();
  }
  auto other = row(0, 1, kGtR, kGtT);
  other.obj_id = 9;
  EXPECT_THROW(evaluate(d, {other}), InputError);
}

TEST(PrecisionCurve, CountsErrorsWithinEachThreshold) {
  std::vector<HypothesisResult> results(4);
  const double te[] = {1.0, 5.0, 12.0, std::numeric_limits<double>::infinity()};
  const double re[] = {2.0, 30.0, 4.0, std::numeric_limits<double>::infinity()};
  for (int i = 0; i < 4; ++i)
    results[i].translation_pct = te[i], results[i].rotation_deg = re[i], results[i].top = i % 2 == 0;
  const auto c = figure7_curves(results);
  ASSERT_EQ(c[0].threshold.size(), 121u);
  EXPECT_DOUBLE_EQ(c[0].threshold.back(), 30.0);
  EXPECT_DOUBLE_EQ(c[2].threshold.back(), 60.0);
  // translation, all: thresholds 0.5 -> 0, 1 -> 1/4, 5 -> 2/4, 12 -> 3/4, 30 -> 3/4
  auto at = [](const PrecisionCurve& curve, double x) {
    for (std::size_t i = 0; i < curve.threshold.size(); ++i)
      if (std::abs(curve.threshold[i] - x) < 1e-9) return curve.precision[i];
    ADD_FAILURE() << "no threshold " << x;
    return -1.0;
  };
  EXPECT_DOUBLE_EQ(at(c[0], 0.5), 0.0);
  EXPECT_DOUBLE_EQ(at(c[0], 1.0), 0.25);
  EXPECT_DOUBLE_EQ(at(c[0], 5.0), 0.5);
  EXPECT_DOUBLE_EQ(at(c[0], 30.0), 0.75);
  // translation, top (hypotheses 0 and 2): 1 -> 1/2, 12 -> 1
  EXPECT_DOUBLE_EQ(at(c[1], 1.0), 0.5);
  EXPECT_DOUBLE_EQ(at(c[1], 12.0), 1.0);
  // rotation, all: 2 -> 1/4, 4 -> 2/4, 30 -> 3/4; top: 4 -> 1
  EXPECT_DOUBLE_EQ(at(c[2], 2.0), 0.25);
  EXPECT_DOUBLE_EQ(at(c[2], 4.0), 0.5);
  EXPECT_DOUBLE_EQ(at(c[2], 30.0), 0.75);
  EXPECT_DOUBLE_EQ(at(c[3], 4.0), 1.0);
  for (const auto& curve : c)
    for (std::size_t i = 1; i < curve.precision.size(); ++i)
      EXPECT_LE(curve.precision[i - 1], curve.precision[i]);
}

TEST(PrecisionCurve, EmptySetIsZero) {
  const auto c = precision_curve({}, kRotationAxis, HypothesisSet::top);
  for (double p : c.precision) EXPECT_EQ(p, 0.0);
}

TEST(ModelsInfo, ReadsDiameterAndSymmetries) {
  const auto info = bop::parse_models_info(R"({
    "1": {"diameter": 52.5, "min_x": -1, "symmetries_continuous": [{"axis": [0, 0, 2], "offset": [1, 2, 3]}]},
    "3": {"diameter": 10, "symmetries_discrete": [[-1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 4, 0, 0, 0, 1]]}
  })", "mem");
  ASSERT_EQ(info.size(), 2u);
  EXPECT_DOUBLE_EQ(info.at(1).diameter, 52.5);
  ASSERT_EQ(info.at(1).symmetries.continuous.size(), 1u);
  EXPECT_TRUE(info.at(1).symmetries.continuous[0].axis.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(info.at(1).symmetries.continuous[0].offset.isApprox(Eigen::Vector3d(1, 2, 3)));
  ASSERT_EQ(info.at(3).symmetries.discrete.size(), 1u);
  EXPECT_DOUBLE_EQ(info.at(3).symmetries.discrete[0](2, 3), 4.0);
  EXPECT_TRUE(info.at(1).centre.isZero());  // an incomplete box is no box
}

TEST(ModelsInfo, ReadsTheBoxCentre) {
  const auto info = bop::parse_models_info(R"({"2": {"diameter": 9, "min_x": -1, "min_y": 2,
    "min_z": 0, "size_x": 4, "size_y": 2, "size_z": 6}})", "mem");
  EXPECT_TRUE(info.at(2).centre.isApprox(Eigen::Vector3d(1, 3, 3)));
}

TEST(ModelsInfo, RejectsMalformedEntries) {
  for (const char* bad : {"[]", "{}", "{\"x\": {\"diameter\": 1}}", "{\"1\": {}}",
                          "{\"1\": {\"diameter\": -2}}",
                          "{\"1\": {\"diameter\": 2, \"symmetries_continuous\": [{\"axis\": [0, 0, 0]}]}}",
                          "{\"1\": {\"diameter\": 2, \"symmetries_discrete\": [[1, 2, 3]]}}",
                          "{\"1\": {\"diameter\": 2, \"symmetries_discrete\": [[2,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]]}}",
                          "not json"}) {
    EXPECT_THROW(bop::parse_models_info(bad, "mem"), InputError) << bad;
  }
}

TEST(Evaluate, LandingTellsThePartADistractorAndNothingApart) {
  Dataset d = two_part_dataset();
  d.models[1].centre = Eigen::Vector3d(20, 0, 0);  // the box centre, off the model origin
  d.models[2] = {30.0, {}};
  d.images[{0, 0}].gt.push_back({2, {kGtR, kGtT + Eigen::Vector3d(0, 200, 0)}});
  const Eigen::Matrix3d flip = rot(180, {0, 0, 1});  // turns the centre to the origin's other side
  const std::vector<bop::ResultRow> rows{
      row(0, 9, kGtR, kGtT + Eigen::Vector3d(0, 0, 20)),                 // 20 mm above part 1
      row(0, 8, kGtR, kGtT + Eigen::Vector3d(0, 195, 0) - kGtR * d.models[1].centre),  // distractor
      row(0, 7, kGtR, kGtT + Eigen::Vector3d(0, -300, 0)),               // on nothing
      row(0, 6, kGtR * flip, kGtT + kGtR * Eigen::Vector3d(40, 0, 0)),  // same centre as part 1
      row(0, 5, kGtR * flip, kGtT),  // origin on part 1's, centre 40 mm away: beyond 26
  };
  const EvalSummary s = evaluate(d, rows);
  EXPECT_EQ(s.results[0].landing, Landing::part);
  EXPECT_EQ(s.results[1].landing, Landing::distractor);
  EXPECT_EQ(s.results[2].landing, Landing::none);
  EXPECT_EQ(s.results[3].landing, Landing::part);
  EXPECT_EQ(s.results[4].landing, Landing::none);
  EXPECT_DOUBLE_EQ(s.all_on_distractor, 0.2);
  EXPECT_DOUBLE_EQ(s.all_on_nothing, 0.4);
  EXPECT_DOUBLE_EQ(s.top_on_distractor, 0.0);
  EXPECT_DOUBLE_EQ(s.top_on_nothing, 0.0);
}

}  // namespace
}  // namespace binpick::eval
