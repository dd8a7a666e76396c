// The instance budget (--instances N): the selection on hand-made poses (best first, score 0 and
// duplicates of one part left out, at most N), and on a synthetic bin of 35 brackets through the
// command line: N = 10 gives more than 5 rows an image, no two on one part; N = 0 gives exactly
// the rows of a run without the option (the paper's one per hypothesis).
#include <gtest/gtest.h>

#include <string>

#include <fmt/format.h>

#include "host/detect/instance_select.hpp"
#include "host/detect/pose_fit.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/train/ppf_model_file.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

Detection pose(double x, double score, std::uint64_t votes, std::uint32_t index) {
  Detection d;
  d.t = Eigen::Vector3d(x, 0, 500);
  d.score = score;
  d.votes = votes;
  d.index = index;
  return d;
}

}  // namespace

TEST(InstanceSelect, BestFirstDistinctPartsWithinBudget) {
  const Eigen::Vector3d centroid(10, 0, 0);  // model frame: posed at R c + t
  std::vector<Detection> poses = {
      pose(0, 0.5, 10, 0),
      pose(5, 0.8, 10, 1),     // 5 mm from the first: the same part, and better
      pose(100, 0.0, 90, 2),   // verification rejected it
      pose(200, 0.6, 10, 3),
      pose(300, 0.6, 20, 4),   // ties 3 on score, more votes: first
      pose(400, 0.3, 10, 5),
  };
  // A turned pose whose centroid lands on pose 3's: a duplicate although t differs.
  Detection turned = pose(0, 0.2, 10, 6);
  turned.R = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  turned.t = Eigen::Vector3d(220, 0, 500);  // R c + t = (210, 0, 500)
  poses.push_back(turned);

  const auto all = select_instances(poses, centroid, 13.0, 100);
  std::vector<std::uint32_t> order;
  for (const auto& d : all) order.push_back(d.index);
  EXPECT_EQ(order, (std::vector<std::uint32_t>{1, 4, 3, 5}));

  const auto two = select_instances(poses, centroid, 13.0, 2);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].index, 1u);
  EXPECT_EQ(two[1].index, 4u);
  // Distance 0: only exact duplicates of the centroid merge; none here.
  EXPECT_EQ(select_instances(poses, centroid, 0.0, 100).size(), 6u);
  EXPECT_TRUE(select_instances({}, centroid, 13.0, 5).empty());
  EXPECT_TRUE(select_instances({pose(0, 0.0, 5, 0)}, centroid, 13.0, 5).empty());
}

TEST(DetectInstances, BudgetOnABinOf35Parts) {
  const fs::path dir = test::fresh_temp_dir("detect_instances");
  const std::string data = (dir / "data").string(), ppfm = (dir / "bracket.ppfm").string();
  auto r = test::run_binpick(fmt::format(
      "synth --model builtin:bracket --out {} --bins 2 --objects 35 --width 640 --height 360",
      data));
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_binpick(fmt::format("train --model builtin:bracket --out {}", ppfm));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto detect = [&](const std::string& name, const std::string& extra) {
    const fs::path csv = dir / name;
    const auto run = test::run_binpick(
        fmt::format("detect --model {} --dataset {} --out {} {}", ppfm, data, csv.string(), extra));
    EXPECT_EQ(run.status, 0) << extra << "\n" << run.err;
    return csv;
  };
  const fs::path paper = detect("paper.csv", "");
  const fs::path zero = detect("zero.csv", "--instances 0");
  const fs::path ten = detect("ten.csv", "--instances 10");
  EXPECT_EQ(test::without_time(test::slurp(zero)), test::without_time(test::slurp(paper)));

  const PpfModel model = read_ppf_model(ppfm);
  const Eigen::Vector3d c = model_centroid(model.cloud);
  const auto rows = bop::read_results_csv(ten);
  for (int scene = 0; scene < 2; ++scene) {
    std::vector<bop::ResultRow> image;
    for (const auto& row : rows)
      if (row.scene_id == scene) image.push_back(row);
    EXPECT_GT(image.size(), 5u) << "scene " << scene;
    EXPECT_LE(image.size(), 10u) << "scene " << scene;
    for (std::size_t i = 0; i < image.size(); ++i) {
      EXPECT_GT(image[i].score, 0.0);
      if (i > 0) {
        EXPECT_GE(image[i - 1].score, image[i].score);
      }
      for (std::size_t j = 0; j < i; ++j) {
        const double apart =
            ((image[i].R * c + image[i].t) - (image[j].R * c + image[j].t)).norm();
        EXPECT_GE(apart, kDuplicateRatio * model.diameter) << "scene " << scene << " rows " << j
                                                           << ", " << i;
      }
    }
  }
  // The paper's setting gives one row a hypothesis: at most 5 an image.
  for (int scene = 0; scene < 2; ++scene) {
    std::size_t n = 0;
    for (const auto& row : bop::read_results_csv(paper)) n += row.scene_id == scene;
    EXPECT_LE(n, 5u);
  }

  // Out of range: one clear message naming the option.
  for (const std::string bad : {"--instances -1", "--instances 1001", "--instances x"}) {
    const auto run = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} {}",
                                                   ppfm, data, (dir / "bad.csv").string(), bad));
    EXPECT_EQ(run.status, 2) << bad;
    EXPECT_NE(run.err.find("--instances"), std::string::npos) << bad << "\n" << run.err;
  }
  fs::remove_all(dir);
}
