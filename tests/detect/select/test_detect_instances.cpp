// The instance budget (--instances N): the selection on hand-made poses (best first, score 0 and
// duplicates of one part left out, at most N), and on a synthetic bin of 35 brackets through the
// command line: N = 10 gives more than 5 rows an image, no two on one part; N = 0 gives exactly
// the rows of a run without the option (the paper's one per hypothesis). The second round of
// highest points (--more-hypotheses) only when no pose is confident. And the budget per image
// from BOP's target list (detect --targets).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/detect/select/instance_select.hpp"
#include "host/detect/refine/pose_fit.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/train/ppf_model_file.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

Detection pose(double x, double score, std::uint64_t votes, std::uint32_t index) {
  Detection d;
  d.t = Eigen::Vector3d(x, 0, 500);
  d.breakdown[kAgreement] = score;  // every other factor neutral
  d.votes = votes;
  d.index = index;
  return d;
}

// Two synthetic bins of 35 brackets (640 x 360) and the bracket's model, in a fresh directory;
// detect() runs detection on them with extra options and returns the results file and stdout.
struct BracketBins {
  fs::path dir;
  std::string data, ppfm;

  explicit BracketBins(const std::string& name) : dir(test::fresh_temp_dir(name)) {
    data = (dir / "data").string();
    ppfm = (dir / "bracket.ppfm").string();
    auto r = test::run_binpick(fmt::format(
        "synth --model builtin:bracket --out {} --bins 2 --objects 35 --width 640 --height 360",
        data));
    EXPECT_EQ(r.status, 0) << r.err;
    r = test::run_binpick(fmt::format("train --model builtin:bracket --out {}", ppfm));
    EXPECT_EQ(r.status, 0) << r.err;
  }
  ~BracketBins() { fs::remove_all(dir); }

  std::pair<fs::path, std::string> detect(const std::string& name,
                                          const std::string& extra) const {
    const fs::path csv = dir / name;
    const auto run = test::run_binpick(
        fmt::format("detect --model {} --dataset {} --out {} {}", ppfm, data, csv.string(), extra));
    EXPECT_EQ(run.status, 0) << extra << "\n" << run.err;
    return {csv, run.out};
  }
};

// The CSV lines of one scene, without the time column.
std::string scene_rows(const fs::path& csv, int scene) {
  std::string out;
  for (bop::ResultRow row : bop::read_results_csv(csv)) {
    row.time = 0;  // the image's seconds differ between runs
    if (row.scene_id == scene) out += bop::format_result_row(row) + "\n";
  }
  return out;
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

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
  const BracketBins bins("detect_instances");
  ASSERT_FALSE(::testing::Test::HasFailure());
  const fs::path& dir = bins.dir;
  const std::string &data = bins.data, &ppfm = bins.ppfm;
  const auto detect = [&](const std::string& name, const std::string& extra) {
    return bins.detect(name, extra).first;
  };
  // The paper's setting: 5 highest points, no second round (--more-hypotheses).
  const fs::path paper = detect("paper.csv", "--more-hypotheses 0");
  const fs::path zero = detect("zero.csv", "--instances 0 --more-hypotheses 0");
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
}

// A second round of highest points (--more-hypotheses, --confident): never confident
// (--confident 1) tries all 10 in every image and refines and ranks them together, exactly as
// --hypotheses 10 does; always confident (--confident 0) gives the rows of --more-hypotheses 0.
// Bad values: one message each.
TEST(DetectMoreHypotheses, SecondRoundOnlyWhenNoPoseIsConfident) {
  const BracketBins bins("detect_more");
  ASSERT_FALSE(::testing::Test::HasFailure());
  const auto rows = [&](const std::string& name, const std::string& extra) {
    return test::without_time(test::slurp(bins.detect(name, extra).first));
  };
  // In height order the first round is the 5 highest points (ranked by the coarse vote, the 5
  // most part-like of the 10: Prerank.*).
  const std::string five = rows("five.csv", "--more-hypotheses 0 --no-prerank");
  EXPECT_EQ(rows("sure.csv", "--confident 0 --no-prerank"), five);
  const std::string ten = rows("ten.csv", "--confident 1");
  EXPECT_EQ(ten, rows("all.csv", "--hypotheses 10 --more-hypotheses 0"));
  // The premise: --confident 1 is not met (every image has a second round), and it was needed.
  for (int scene = 0; scene < 2; ++scene) {
    std::size_t n5 = 0, n10 = 0;
    double top5 = 0;
    for (const auto& row : bop::read_results_csv(bins.dir / "five.csv"))
      if (row.scene_id == scene) ++n5, top5 = std::max(top5, row.score);
    for (const auto& row : bop::read_results_csv(bins.dir / "ten.csv")) n10 += row.scene_id == scene;
    EXPECT_EQ(n5, 5u) << "scene " << scene;
    EXPECT_LT(top5, 1.0) << "scene " << scene;
    EXPECT_EQ(n10, 10u) << "scene " << scene;
  }
  for (const std::string bad : {"--more-hypotheses -1", "--more-hypotheses 1001",
                                "--confident 1.5", "--confident -0.1", "--confident nan"}) {
    const auto run = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} {}",
                                                   bins.ppfm, bins.data,
                                                   (bins.dir / "bad.csv").string(), bad));
    EXPECT_EQ(run.status, 2) << bad;
    EXPECT_NE(run.err.find(bad.substr(0, bad.find(' '))), std::string::npos) << bad << "\n" << run.err;
  }
}

// A robot's mode (--stop-at-confident, --budget-ms): the hypotheses one at a time in their
// order. Always confident (--confident 0): one hypothesis an image, the first's rows, and
// --verbose says it stopped; never confident: all ten, one at a time. A budget spent at once
// (0.001 ms) stops after the first hypothesis too. The summary gives the time to the first
// confident pose. Not with --instances.
TEST(DetectRobotMode, StopsAtTheFirstConfidentPoseOrWhenTheBudgetIsSpent) {
  const BracketBins bins("detect_robot");
  ASSERT_FALSE(::testing::Test::HasFailure());
  const auto per_scene = [](const fs::path& csv) {
    std::map<int, std::size_t> n;
    for (const auto& row : bop::read_results_csv(csv)) ++n[row.scene_id];
    return n;
  };
  const auto [sure, sure_out] = bins.detect("sure.csv", "--stop-at-confident --confident 0 --verbose");
  for (const auto& [scene, rows] : per_scene(sure)) EXPECT_EQ(rows, 1u) << "scene " << scene;
  EXPECT_NE(sure_out.find("stopped after 1 of 10 hypotheses: a confident pose (--stop-at-confident)"),
            std::string::npos)
      << sure_out;
  EXPECT_NE(sure_out.find("the first confident pose after"), std::string::npos) << sure_out;
  EXPECT_NE(sure_out.find("a confident pose in 2 images, the first after"), std::string::npos)
      << sure_out;
  // The first hypothesis' pose is the one a first round of one hypothesis (of the same 10,
  // in the same order) ranks first.
  const auto [one, one_out] =
      bins.detect("one.csv", "--hypotheses 1 --more-hypotheses 9 --confident 0");
  EXPECT_EQ(scene_rows(sure, 0), scene_rows(one, 0));
  EXPECT_EQ(scene_rows(sure, 1), scene_rows(one, 1));

  const auto [never, never_out] = bins.detect("never.csv", "--stop-at-confident --confident 1");
  for (const auto& [scene, rows] : per_scene(never)) EXPECT_EQ(rows, 10u) << "scene " << scene;
  EXPECT_EQ(never_out.find("a confident pose in"), std::string::npos) << never_out;

  const auto [spent, spent_out] = bins.detect("spent.csv", "--budget-ms 0.001 --verbose");
  for (const auto& [scene, rows] : per_scene(spent)) EXPECT_EQ(rows, 1u) << "scene " << scene;
  EXPECT_NE(spent_out.find("stopped after 1 of 10 hypotheses: the budget of 0.001 ms spent"),
            std::string::npos)
      << spent_out;

  for (const std::string bad : {"--budget-ms -1", "--budget-ms nan",
                                "--stop-at-confident --instances 3", "--budget-ms 5 --instances 2"}) {
    const auto run = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} {}",
                                                   bins.ppfm, bins.data,
                                                   (bins.dir / "bad.csv").string(), bad));
    EXPECT_EQ(run.status, 2) << bad;
    EXPECT_NE(run.err.find(bad.find("instances") != std::string::npos ? "does not go with" : "budget-ms"),
              std::string::npos)
        << bad << "\n" << run.err;
  }
}

// detect --targets FILE (BOP's test_targets_bop19.json as the instance budget): each image gets
// exactly the rows of `--instances inst_count` on that image, images not listed (or listing
// another obj_id only) get none and are not read, and bad target files or --targets with
// --instances are refused with one message.
TEST(DetectTargets, BudgetPerImageFromTheTargetList) {
  const BracketBins bins("detect_targets");
  ASSERT_FALSE(::testing::Test::HasFailure());
  const fs::path& dir = bins.dir;
  const std::string &data = bins.data, &ppfm = bins.ppfm;
  const auto detect = [&](const std::string& name, const std::string& extra) {
    return bins.detect(name, extra);
  };

  // The dataset's own list (synth writes it): every image is a target of obj_id 1.
  const fs::path bop19 = fs::path(data) / "test_targets_bop19.json";
  std::map<int, int> count;
  for (const auto& e : nlohmann::json::parse(test::slurp(bop19)))
    count[e["scene_id"].get<int>()] = e["inst_count"].get<int>();
  ASSERT_EQ(count.size(), 2u);
  const auto [listed, listed_log] = detect("listed.csv", "--targets " + bop19.string());
  for (const auto& [scene, n] : count) {
    ASSERT_GT(n, 5) << "scene " << scene;  // more than the paper's 5 rows: the budget shows
    const auto [alone, log] =
        detect(fmt::format("alone{}.csv", scene), fmt::format("--instances {} --scenes {}", n, scene));
    EXPECT_FALSE(scene_rows(alone, scene).empty());
    EXPECT_EQ(scene_rows(listed, scene), scene_rows(alone, scene)) << "scene " << scene;
  }

  // A hand-made list: scene 1 only, 3 instances; scene 0 lists another object only.
  const fs::path mine = dir / "mine.json";
  write(mine, R"([{"scene_id": 0, "im_id": 0, "obj_id": 7, "inst_count": 2},
                  {"scene_id": 1, "im_id": 0, "obj_id": 1, "inst_count": 3}])");
  const auto [three, three_log] = detect("three.csv", "--targets " + mine.string());
  EXPECT_EQ(scene_rows(three, 0), "");
  const auto [alone3, log3] = detect("alone3.csv", "--instances 3 --scenes 1");
  EXPECT_EQ(scene_rows(three, 1), scene_rows(alone3, 1));
  EXPECT_LE(bop::read_results_csv(three).size(), 3u);
  EXPECT_NE(three_log.find("1 without a target not read"), std::string::npos) << three_log;

  // Refused with one message: each names what is wrong.
  write(dir / "bad.json", R"({"scene_id": 1})");
  write(dir / "huge.json", R"([{"scene_id": 1, "im_id": 0, "obj_id": 1, "inst_count": 5000}])");
  const std::pair<std::string, std::string> bad[] = {
      {"--targets " + (dir / "bad.json").string(), "bad.json"},
      {"--targets " + (dir / "huge.json").string(), "at most 1000"},
      {"--targets " + (dir / "none.json").string(), "none.json"},
      {"--targets " + bop19.string() + " --instances 4", "--instances"},
  };
  for (const auto& [args, says] : bad) {
    const auto run = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} {}",
                                                   ppfm, data, (dir / "x.csv").string(), args));
    EXPECT_EQ(run.status, 2) << args;
    EXPECT_NE(run.err.find(says), std::string::npos) << args << "\n" << run.err;
    EXPECT_FALSE(fs::exists(dir / "x.csv")) << args;
  }
}
