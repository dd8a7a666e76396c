// BOP's matching, recall and average recall on hand-made errors, its targets, and bop_scores()
// on a tiny hand-written dataset (a low-visibility instance, a duplicate estimate, the
// inst_count budget).
#include <gtest/gtest.h>

#include <fstream>

#include <Eigen/Geometry>

#include "host/core/error.hpp"
#include "host/eval/metrics/bop_scores.hpp"
#include "host/eval/metrics/bop_targets.hpp"
#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/bop_models.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/test_meshes.hpp"

namespace binpick::eval {
namespace {

namespace fs = std::filesystem;

EstimateErrors errors(std::vector<std::pair<int, double>> e) { return {std::move(e)}; }

TEST(BopMatching, EachEstimateTakesTheNearestFreeInstanceBelowTheThreshold) {
  // The first takes instance 1 (the smaller error), the second finds it taken and takes 0.
  const std::vector<EstimateErrors> two{errors({{0, 0.04}, {1, 0.03}}),
                                        errors({{0, 0.04}, {1, 0.01}})};
  EXPECT_EQ(matched_instances(two, 0.05), 2);
  // Below the threshold strictly: 0.04 is not below 0.04.
  EXPECT_EQ(matched_instances(two, 0.04), 1);
  // A duplicate of an estimate finds its instance taken.
  const std::vector<EstimateErrors> duplicate{errors({{0, 0.01}}), errors({{0, 0.01}})};
  EXPECT_EQ(matched_instances(duplicate, 0.05), 1);
  EXPECT_EQ(matched_instances({}, 0.05), 0);
}

TEST(BopMatching, RecallPerThresholdAndItsAverage) {
  // obj 1: 2 targets, one estimate at 0.12 and one at 0.33; obj 2: 1 target, missed.
  const std::vector<TargetGroup> groups{{1, 2, {errors({{0, 0.12}}), errors({{1, 0.33}})}},
                                        {2, 1, {}}};
  const auto t = arange(0.05, 0.51, 0.05);
  const MetricRecall r = recall_over_thresholds(groups, t);
  ASSERT_EQ(r.overall.recall.size(), 10u);
  // thresholds 0.05, 0.10: none; 0.15 .. 0.30: one of 3; 0.35 .. 0.50: two of 3.
  EXPECT_DOUBLE_EQ(r.overall.recall[1], 0.0);
  EXPECT_DOUBLE_EQ(r.overall.recall[2], 1.0 / 3);
  EXPECT_DOUBLE_EQ(r.overall.recall[6], 2.0 / 3);
  EXPECT_NEAR(r.overall.average, (4 * (1.0 / 3) + 4 * (2.0 / 3)) / 10, 1e-12);
  ASSERT_EQ(r.objects.size(), 2u);
  EXPECT_EQ(r.objects[0].targets, 2);
  EXPECT_NEAR(r.objects[0].curve.average, (4 * 0.5 + 4 * 1.0) / 10, 1e-12);
  EXPECT_DOUBLE_EQ(r.objects[1].curve.average, 0.0);
}

TEST(BopMatching, ThresholdsAreNumpysArange) {
  const auto mssd = bop_mssd_thresholds();
  ASSERT_EQ(mssd.size(), 10u);
  EXPECT_EQ(mssd[2], 0.05 + 2 * 0.05);  // 0.15000000000000002, as numpy makes it
  EXPECT_EQ(mssd[9], 0.05 + 9 * 0.05);
  const auto mspd = bop_mspd_thresholds();
  ASSERT_EQ(mspd.size(), 10u);
  EXPECT_EQ(mspd.front(), 5.0);
  EXPECT_EQ(mspd.back(), 50.0);
}

TEST(BopTargets, TheMostVisibleInstancesOfEachObjectAreTargets) {
  EvalImage image;
  image.gt = {{1, {}}, {1, {}}, {2, {}}, {1, {}}};
  image.visib_fract = {0.05, 0.9, 0.7, 0.5};
  EXPECT_EQ(target_instances(image, {{1, 2}}), (std::vector<bool>{false, true, false, true}));
  EXPECT_EQ(target_instances(image, {{1, 1}, {2, 1}}),
            (std::vector<bool>{false, true, true, false}));
  image.visib_fract.clear();  // no scene_gt_info.json: all equally visible, first ones first
  EXPECT_EQ(target_instances(image, {{1, 2}}), (std::vector<bool>{true, true, false, false}));
}

TEST(BopTargets, ParsesTheToolkitsFileAndRejectsBadEntries) {
  const auto t = parse_bop_targets(
      R"([{"scene_id": 1, "im_id": 2, "obj_id": 3, "inst_count": 4},
          {"scene_id": 1, "im_id": 2, "obj_id": 5, "inst_count": 0}])", "t.json");
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t.at({1, 2}), (std::map<int, int>{{3, 4}}));
  EXPECT_THROW(parse_bop_targets("{}", "t.json"), InputError);
  EXPECT_THROW(parse_bop_targets(R"([{"scene_id": 1, "im_id": 2, "obj_id": 3}])", "t.json"),
               InputError);
  EXPECT_THROW(parse_bop_targets(
                   R"([{"scene_id": 1, "im_id": 2, "obj_id": 3, "inst_count": -1}])", "t.json"),
               InputError);
  EXPECT_THROW(
      parse_bop_targets(R"([{"scene_id": 1, "im_id": 2, "obj_id": 3, "inst_count": 1},
                            {"scene_id": 1, "im_id": 2, "obj_id": 3, "inst_count": 2}])",
                        "t.json"),
      InputError);
}

// One image of three boxes (obj 1, 40 x 20 x 10 mm) 100 mm apart: instance 0 is hidden
// (visib_fract 0.05, not a target), 1 and 2 are targets (inst_count 2).
struct TinyDataset {
  fs::path root = test::fresh_temp_dir("bop_scores");
  std::vector<bop::GroundTruth> gt;
  explicit TinyDataset(bool with_info = true) {
    fs::create_directories(root / "test/000000");
    write_bop_models(root, test::box({40, 20, 10}), 1, {});
    bop::write_camera(root / "camera.json", {500, 500, 320, 240, 640, 480, 1.0});
    for (int i = 0; i < 3; ++i)
      gt.push_back({1, {Eigen::Matrix3d::Identity(), {100.0 * (i - 1), 0, 700}}});
    bop::write_scene_gt(root / "test/000000/scene_gt.json", {{0, gt}});
    bop::SceneCamera cam;
    cam.K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
    bop::write_scene_cameras(root / "test/000000/scene_camera.json", {{0, cam}});
    if (with_info) {
      std::vector<bop::GroundTruthInfo> info(3);
      info[0].visib_fract = 0.05, info[1].visib_fract = 0.8, info[2].visib_fract = 0.6;
      bop::write_scene_gt_info(root / "test/000000/scene_gt_info.json", {{0, info}});
    }
  }
  ~TinyDataset() { fs::remove_all(root); }
  bop::ResultRow at(int instance, double score, double dx = 0) const {
    bop::ResultRow r;
    r.R = gt[instance].model_to_camera.R;
    r.t = gt[instance].model_to_camera.t + Eigen::Vector3d(dx, 0, 0);
    r.score = score;
    return r;
  }
};

TEST(BopScores, CountsTargetsOnlyAndTheInstCountBestEstimates) {
  TinyDataset d;
  const Dataset dataset = load_dataset(d.root);
  const double diameter = dataset.models.at(1).diameter;
  // By score: on the hidden instance (matches nothing), on instance 1 (right), its duplicate,
  // and one 0.32 d off instance 2 (would count at thresholds above 0.32, but is last in score).
  const std::vector<bop::ResultRow> rows{d.at(1, 0.9), d.at(2, 0.1, 0.32 * diameter),
                                         d.at(0, 0.95), d.at(1, 0.8)};
  const BopScores s = bop_scores(dataset, rows);
  EXPECT_EQ(s.targets, 2);
  EXPECT_EQ(s.estimates, 2);
  EXPECT_TRUE(s.image_width_known);
  EXPECT_EQ(s.vertices, d.root / "models");
  for (double r : s.mssd.overall.recall) EXPECT_DOUBLE_EQ(r, 0.5);
  for (double r : s.mspd.overall.recall) EXPECT_DOUBLE_EQ(r, 0.5);
  EXPECT_DOUBLE_EQ(s.average_recall, 0.5);

  // With the budget spent on the two right ones, instance 2 counts from threshold 0.35 on.
  const BopScores better = bop_scores(dataset, {d.at(1, 0.9), d.at(2, 0.8, 0.32 * diameter)});
  EXPECT_DOUBLE_EQ(better.mssd.overall.recall[5], 0.5);  // 0.30: 0.32 d is not below it...
  EXPECT_DOUBLE_EQ(better.mssd.overall.recall[6], 1.0);  // ...0.35 is above it
  EXPECT_NEAR(better.mssd.overall.average, (6 * 0.5 + 4 * 1.0) / 10, 1e-12);
}

TEST(BopScores, WithoutVisibilityEveryInstanceIsATarget) {
  TinyDataset d(false);
  const Dataset dataset = load_dataset(d.root);
  const BopScores s = bop_scores(dataset, {d.at(1, 0.9), d.at(0, 0.95), d.at(1, 0.8)});
  EXPECT_EQ(s.targets, 3);
  EXPECT_EQ(s.estimates, 3);
  EXPECT_NEAR(s.mssd.overall.average, 2.0 / 3, 1e-12);
}

TEST(BopScores, ReadsTheTargetsFileAndModelsEval) {
  TinyDataset d;
  {
    std::ofstream(d.root / "test_targets_bop19.json")
        << R"([{"scene_id": 0, "im_id": 0, "obj_id": 1, "inst_count": 1}])";
  }
  fs::create_directories(d.root / "models_eval");
  fs::copy_file(d.root / "models/obj_000001.ply", d.root / "models_eval/obj_000001.ply");
  const Dataset dataset = load_dataset(d.root);
  const BopScores s = bop_scores(dataset, {d.at(2, 0.9), d.at(1, 0.8)});
  EXPECT_EQ(s.targets, 1);  // the most visible one: instance 1
  EXPECT_EQ(s.estimates, 1);  // and only the best-scored estimate, which is on instance 2
  EXPECT_DOUBLE_EQ(s.average_recall, 0.0);
  EXPECT_EQ(s.vertices, d.root / "models_eval");
  {
    std::ofstream(d.root / "test_targets_bop19.json")
        << R"([{"scene_id": 0, "im_id": 9, "obj_id": 1, "inst_count": 1}])";
  }
  EXPECT_THROW(bop_scores(dataset, {}), InputError);
  {
    std::ofstream(d.root / "test_targets_bop19.json")
        << R"([{"scene_id": 0, "im_id": 0, "obj_id": 7, "inst_count": 1}])";
  }
  EXPECT_THROW(bop_scores(dataset, {}), InputError);
}

TEST(BopScores, WithoutTheModelFileTheyAreUnavailableNotAnError) {
  TinyDataset d;
  fs::remove(d.root / "models/obj_000001.ply");
  const BopScores s = bop_scores(load_dataset(d.root), {d.at(1, 0.9)});
  EXPECT_NE(s.unavailable.find("obj_000001.ply"), std::string::npos) << s.unavailable;
  {
    std::ofstream(d.root / "models/obj_000001.ply") << "not a ply";
  }
  EXPECT_THROW(bop_scores(load_dataset(d.root), {d.at(1, 0.9)}), InputError);
}

}  // namespace
}  // namespace binpick::eval
