// `binpick detect` as a user runs it: the results CSV (format, best first, same bytes on a rerun
// except the time column), resuming a batch, --scenes, --params with the command line winning,
// the --cloud path, and bad input (missing files, a model of another format version, an all-zero
// depth image, NaN points) with one clear message and no crash; a fixed cell's bin saved and
// given. Also the results CSV reader.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include <cmath>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/detect/params/bin_pose_file.hpp"
#include "host/detect/verify/score.hpp"
#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/core/error.hpp"
#include "host/app/options/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/train/surface_sampling.hpp"
#include "tests/detect/bin/bin_fit_check.hpp"
#include "tests/detect/bin/bin_scene.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

// A BOP dataset of `scenes` images of the bracket at different poses over a floor (point splat
// z-buffer, 320 x 240). zero_depth makes every image empty.
void make_dataset(const fs::path& dir, int scenes, bool zero_depth = false) {
  const Mesh mesh = cli::load_part({"builtin:bracket", {}}).mesh;
  const PointCloud samples = sample_surface(mesh, 300000);
  const std::uint32_t w = 320, h = 240;
  const double f = 600, cx = (w - 1) / 2.0, cy = (h - 1) / 2.0, scale = 0.1;
  fs::create_directories(dir);
  bop::write_camera(dir / "camera.json", {f, f, cx, cy, w, h, scale});
  for (int s = 0; s < scenes; ++s) {
    const fs::path sd = dir / "test" / fmt::format("{:06d}", s);
    fs::create_directories(sd / "depth");
    Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
    T.linear() = Eigen::AngleAxisf(0.5f + s, Eigen::Vector3f(1, 2, 3 - s).normalized()).toRotationMatrix();
    T.translation() = Eigen::Vector3f(5.0f * s, -4.0f, 600.0f);
    std::vector<float> z(w * h, 650.0f);
    for (const auto& m : samples.points) {
      const Eigen::Vector3f p = T * m;
      const long u = std::lround(f * p.x() / p.z() + cx), v = std::lround(f * p.y() / p.z() + cy);
      if (u >= 0 && v >= 0 && u < long(w) && v < long(h)) z[v * w + u] = std::min(z[v * w + u], p.z());
    }
    GrayImage<std::uint16_t> depth{w, h, std::vector<std::uint16_t>(w * h, 0)};
    if (!zero_depth)
      for (std::size_t k = 0; k < z.size(); ++k) depth.pixels[k] = std::uint16_t(std::lround(z[k] / scale));
    write_png(sd / "depth" / "000000.png", depth);
    bop::SceneCamera cam;
    cam.K << f, 0, cx, 0, f, cy, 0, 0, 1;
    cam.depth_scale = scale;
    bop::write_scene_cameras(sd / "scene_camera.json", {{0, cam}});
    bop::write_scene_gt(sd / "scene_gt.json", {{0, {{1, bop::Pose::from(T.cast<double>())}}}});
  }
}

class DetectCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::fresh_temp_dir("detect_cli"));
    model_ = (*dir_ / "bracket.ppfm").string();
    const auto r = test::run_binpick("train --model builtin:bracket --out " + model_);
    ASSERT_EQ(r.status, 0) << r.err;
    make_dataset(*dir_ / "data", 3);
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(*dir_, ec);
    delete dir_;
    dir_ = nullptr;
  }
  static fs::path* dir_;
  static std::string model_;
};
fs::path* DetectCli::dir_ = nullptr;
std::string DetectCli::model_;

}  // namespace

TEST_F(DetectCli, WritesResultsBestFirstResumesAndIsDeterministic) {
  const fs::path out = *dir_ / "run1" / "results.csv";
  fs::create_directories(out.parent_path());
  const std::string cmd = fmt::format("detect --model {} --dataset {} --out {} --hypotheses 3",
                                      model_, (*dir_ / "data").string(), out.string());
  auto r = test::run_binpick(cmd);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("ms per hypothesis"), std::string::npos) << r.out;
  const auto rows = bop::read_results_csv(out);
  ASSERT_GE(rows.size(), 3u);
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (rows[i].scene_id == rows[i - 1].scene_id) {
      EXPECT_GE(rows[i - 1].score, rows[i].score);
      EXPECT_EQ(rows[i - 1].time, rows[i].time);  // per image
    } else {
      EXPECT_GT(rows[i].scene_id, rows[i - 1].scene_id);
    }
  for (const auto& row : rows) {
    EXPECT_NEAR(row.R.determinant(), 1.0, 1e-6);
    EXPECT_GT(row.score, 0);
    EXPECT_GT(row.time, 0);
  }
  // Top row of each scene: on the bracket (how close is test_detect_e2e's business; from some
  // views a thin part is nearly ambiguous).
  for (int s = 0; s < 3; ++s) {
    const auto gt = bop::read_scene_gt(*dir_ / "data" / "test" / fmt::format("{:06d}", s) / "scene_gt.json");
    for (const auto& row : rows)
      if (row.scene_id == s) {
        EXPECT_LT((row.t - gt.at(0)[0].model_to_camera.t).norm(), 0.6 * 52.0) << s;
        break;
      }
  }
  const std::string first = test::slurp(out);
  EXPECT_TRUE(first.starts_with("scene_id,im_id,obj_id,score,R,t,time\n"));
  for (const auto& row : rows) EXPECT_LE(row.score, 1.0);  // the verified score, not votes
  // Beside it, one line a detection with its votes, in the same order.
  const std::string details = test::slurp(out.parent_path() / "results.details.csv");
  EXPECT_TRUE(details.starts_with("scene_id,im_id,rank,hypothesis,candidate,score,votes,"));
  // Hypotheses skipped before voting (here a highest point on the floor, by the flat-region
  // test) have a line too: no rank, score 0, and their reason.
  std::istringstream all_lines(details);
  std::string line;
  std::getline(all_lines, line);
  std::vector<std::string> ranked;
  while (std::getline(all_lines, line)) {
    const std::size_t rank_at = line.find(',', line.find(',') + 1) + 1;
    if (line[rank_at] != ',') {
      ranked.push_back(line);
      continue;
    }
    // Score 0, no votes or points, and no factor: the hypothesis was never verified.
    EXPECT_NE(line.find(",0.000000,0,0,0" + std::string(kScoreFactorCount, ',') + ",\"skipped: "),
              std::string::npos)
        << line;
  }
  ASSERT_EQ(ranked.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    line = ranked[i];
    EXPECT_TRUE(line.starts_with(fmt::format("{},{},", rows[i].scene_id, rows[i].im_id))) << line;
    EXPECT_NE(line.find(fmt::format(",{:.6f},", rows[i].score)), std::string::npos) << line;
  }
  // The golden rule of the score (score.hpp): its factors, as details.csv writes them, combine to
  // the score of every row (up to the six decimals of each cell).
  std::size_t nonzero = 0;
  for (const std::string& row : ranked) {
    std::vector<std::string> cells;
    std::stringstream cut(row);
    for (std::string cell; cells.size() < 9 + kScoreFactorCount && std::getline(cut, cell, ',');)
      cells.push_back(cell);
    ASSERT_EQ(cells.size(), 9 + kScoreFactorCount) << row;
    const auto factor = [&](ScoreFactor f) { return cells[9 + f]; };
    ScoreBreakdown b;
    for (std::size_t f = 0; f < kScoreFactorCount; ++f)
      if (!factor(ScoreFactor(f)).empty()) b.factor[f] = std::stod(factor(ScoreFactor(f)));
    const double score = std::stod(cells[5]);
    EXPECT_NEAR(b.score(), score, 2e-6 * int(kScoreFactorCount)) << row;
    nonzero += score > 0;
  }
  EXPECT_GT(nonzero, rows.size() / 2);

  // A rerun resumes: every scene was done before, the merged CSV is the same bytes.
  r = test::run_binpick(cmd);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("3 scenes (3 done before)"), std::string::npos) << r.out;
  EXPECT_EQ(test::slurp(out), first);

  // An interrupted run: one scene's part missing is redone; other options start over. Either
  // way the same detections (only the time column may differ).
  fs::remove(fs::path(out.string() + ".parts") / "scene_000001.csv");
  r = test::run_binpick(cmd);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("3 scenes (2 done before)"), std::string::npos) << r.out;
  EXPECT_EQ(test::without_time(test::slurp(out)), test::without_time(first));
  r = test::run_binpick(cmd + " --cluster-angle 19.5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("3 scenes (0 done before)"), std::string::npos) << r.out;

  // --scenes and --verbose
  const fs::path sub = *dir_ / "run1" / "subset.csv";
  r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} --scenes 1-2 --verbose",
                                    model_, (*dir_ / "data").string(), sub.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("scene 2 image 0"), std::string::npos) << r.out;
  // Each detection's score is shown as its factors (score.hpp), then the evidence behind them.
  EXPECT_NE(r.out.find(" = agreement 0."), std::string::npos) << r.out;
  // The ray spread is on by default and says what it found per detection.
  EXPECT_NE(r.out.find("mm spread along the rays beyond the noise"), std::string::npos) << r.out;
  for (const auto& row : bop::read_results_csv(sub)) EXPECT_GE(row.scene_id, 1);
}

TEST_F(DetectCli, ParamsFileAppliesAndCommandLineWins) {
  const fs::path params = *dir_ / "params.json";
  // One highest point and no second round (a 5 % reference set is seldom confident).
  { std::ofstream(params) << R"({"hypotheses": 1, "more_hypotheses": 0, "ref_ratio": 0.05})"; }
  const fs::path out = *dir_ / "params.csv";
  auto r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} --params {} --scenes 0",
                                         model_, (*dir_ / "data").string(), out.string(), params.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(bop::read_results_csv(out).size(), 1u);
  r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} --params {} --scenes 0 --hypotheses 2",
                                    model_, (*dir_ / "data").string(), out.string(), params.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(bop::read_results_csv(out).size(), 2u);
  { std::ofstream(params) << R"({"hypotheses": 1, "no_such_thing": 3})"; }
  r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} --params {}", model_,
                                    (*dir_ / "data").string(), out.string(), params.string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no_such_thing"), std::string::npos) << r.err;
  // Each verification test's parameter, from the file and as an option, is checked alike: one
  // message naming it and its range, exit status 2.
  const auto refused_in_file = [&](const std::string& json, const std::string& message) {
    { std::ofstream(params) << json; }
    const auto r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} --params {}",
                                                 model_, (*dir_ / "data").string(), out.string(),
                                                 params.string()));
    EXPECT_EQ(r.status, 2) << json;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  };
  const auto refused_as_option = [&](const std::string& option, const std::string& message) {
    const auto r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} {}", model_,
                                                 (*dir_ / "data").string(), out.string(), option));
    EXPECT_EQ(r.status, 2) << option;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  };
  refused_in_file(R"({"verify_ray": 2})", "verify-ray 2 must be in [0, 1]");
  refused_in_file(R"({"verify_through": -1})", "verify-through -1 must be in [0, 100]");
  // A parameter's older name is still read from a file, and named by its name now.
  refused_in_file(R"({"verify_twin": 1.5})", "verify-lookalike-holes 1.5 must be in [0, 1]");
  refused_as_option("--verify-lookalike-holes -0.1",
                    "verify-lookalike-holes -0.1 must be in [0, 1]");
  refused_in_file(R"({"verify_edge": 11})", "verify-edge 11 must be in [0, 10]");
  refused_in_file(R"({"flat_region": 0.5})", "flat-region 0.5 must be in {0} or [1, 100]");
  refused_as_option("--flat-region 101", "flat-region 101 must be in {0} or [1, 100]");
  // On/off parameters are flags (--over-rim, --no-over-rim); files may hold true/false or 1/0.
  refused_in_file(R"({"highest-up": 2})", "'highest-up' must be true or false (or 1 or 0)");
  refused_in_file(R"({"over-rim": "yes"})", "'over-rim' must be true or false (or 1 or 0)");
  refused_as_option("--through-walls 3", "not expected: 3");
  refused_as_option("--over-rim 2", "not expected: 2");
  refused_as_option("--highest-up -1", "-1");
  refused_as_option("--verify-edge nan", "verify-edge");
  refused_in_file(R"({"verify_lookalike": 1.5})", "verify-lookalike 1.5 must be in [0, 1]");
  refused_as_option("--verify-lookalike -1", "verify-lookalike");
  refused_in_file(R"({"verify_area": 10.5})", "verify-area 10.5 must be in [0, 10]");
  refused_as_option("--verify-area -1", "verify-area -1 must be in [0, 10]");
  refused_in_file(R"({"verify_rival": 101})", "verify-rival 101 must be in [0, 100]");
  refused_as_option("--verify-rival -1", "verify-rival -1 must be in [0, 100]");
  refused_in_file(R"({"bucket_cap": -1})", "bucket-cap -1 must be in [0, 10000]");
  refused_as_option("--bucket-cap inf", "bucket-cap inf must be in [0, 10000]");
  refused_in_file(R"({"plane_search": 2})", "plane-search 2 must be in [0, 1]");
  refused_as_option("--plane-search -0.5", "plane-search -0.5 must be in [0, 1]");
  refused_in_file(R"({"noise_voxel": 0.5})", "noise-voxel 0.5 must be in [1, 4]");
  refused_as_option("--noise-voxel 5", "noise-voxel 5 must be in [1, 4]");
  refused_in_file(R"({"more_hypotheses": 1001})", "more-hypotheses 1001 must be in [0, 1000]");
  refused_in_file(R"({"confident": 2})", "confident 2 must be in [0, 1]");
  // A capped table detects too.
  r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} --scenes 0 --hypotheses 1 --more-hypotheses 0 --bucket-cap 3",
                                    model_, (*dir_ / "data").string(), out.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(bop::read_results_csv(out).size(), 1u);
}

TEST_F(DetectCli, CloudPath) {
  // The cloud of scene 0 as a PLY without normals: x y z per vertex.
  const Mesh mesh = cli::load_part({"builtin:bracket", {}}).mesh;
  const PointCloud samples = sample_surface(mesh, 20000);
  const auto gt = bop::read_scene_gt(*dir_ / "data" / "test" / "000000" / "scene_gt.json");
  const Eigen::Isometry3d T = gt.at(0)[0].model_to_camera.isometry();
  std::string ply = fmt::format("ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\n"
                                "property float y\nproperty float z\nend_header\n", 0);
  std::string body;
  std::size_t n = 0;
  for (std::size_t i = 0; i < samples.points.size(); ++i) {
    const Eigen::Vector3d nc = T.linear() * samples.normals[i].cast<double>();
    const Eigen::Vector3d p = T * samples.points[i].cast<double>();
    if (nc.dot(p) >= 0) continue;  // facing away from the camera
    body += fmt::format("{} {} {}\n", p.x(), p.y(), p.z());
    ++n;
  }
  ply = fmt::format("ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n", n) + body;
  const fs::path cloud = *dir_ / "cloud.ply", out = *dir_ / "cloud.csv";
  { std::ofstream(cloud) << ply; }
  auto r = test::run_binpick(fmt::format("detect --model {} --cloud {} --out {}", model_, cloud.string(), out.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = bop::read_results_csv(out);
  ASSERT_FALSE(rows.empty());
  EXPECT_LT((rows[0].t - T.translation()).norm(), 5.0);
  // NaN points
  { std::ofstream(cloud) << "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                            "property float z\nend_header\n0 0 600\nnan 1 600\n"; }
  r = test::run_binpick(fmt::format("detect --model {} --cloud {} --out {}", model_, cloud.string(), out.string()));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("cloud.ply"), std::string::npos) << r.err;
}

TEST_F(DetectCli, BadInputGetsOneClearMessage) {
  const std::string data = (*dir_ / "data").string(), out = (*dir_ / "bad.csv").string();
  struct Case { std::string args, message; };
  const fs::path zero = *dir_ / "zero";
  make_dataset(zero, 1, true);
  // A model file of another format version.
  std::string bytes = test::slurp(model_);
  bytes[8] = char(99);
  const fs::path old_model = *dir_ / "old.ppfm";
  { std::ofstream(old_model, std::ios::binary) << bytes; }
  const std::vector<Case> cases = {
      {fmt::format("detect --model {}/missing.ppfm --dataset {} --out {}", dir_->string(), data, out), "missing.ppfm"},
      {fmt::format("detect --model {} --dataset {} --out {}", old_model.string(), data, out), "version"},
      {fmt::format("detect --model {} --dataset {}/nope --out {}", model_, data, out), "nope"},
      {fmt::format("detect --model {} --dataset {} --out {}", model_, zero.string(), out), "no valid pixel"},
      {fmt::format("detect --model {} --dataset {} --out {} --ref-ratio 0", model_, data, out), "--ref-ratio"},
      {fmt::format("detect --model {} --dataset {} --out {} --hypotheses -1", model_, data, out), "--hypotheses"},
      {fmt::format("detect --model {} --dataset {} --out {} --scenes 7", model_, data, out), "scene 7"},
      {fmt::format("detect --model {} --dataset {} --out {} --scenes x", model_, data, out), "--scenes"},
      {fmt::format("detect --model {} --out {}", model_, out), "--dataset"},
      {fmt::format("detect --model {} --dataset {} --out {}/no/dir.csv", model_, data, dir_->string()), "does not exist"},
  };
  for (const Case& c : cases) {
    const auto r = test::run_binpick(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
  }
  // A missing depth image names the file.
  fs::remove(*dir_ / "data" / "test" / "000002" / "depth" / "000000.png");
  const auto r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} --scenes 2", model_, data, out));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("000002"), std::string::npos) << r.err;
  make_dataset(*dir_ / "data", 3);
}

// --roi, --bin and --bin-margin: malformed, inverted, NaN or meaningless values get one clear
// message naming the option (or the --params file's key) and exit 2; --bin auto on images with no
// bin warns once and detects in the whole image; --verbose says what the mask kept.
TEST_F(DetectCli, BinAndRoiOptions) {
  const std::string data = (*dir_ / "data").string(), out = (*dir_ / "bin.csv").string();
  const std::string base = fmt::format("detect --model {} --dataset {} --out {} ", model_, data, out);
  struct Case { std::string args, message; };
  const std::vector<Case> cases = {
      {"--roi camera:1,2,3", "--roi 'camera:1,2,3': not six finite numbers"},
      {"--roi camera:0,0,0,-1,1,1", "inverted along x"},
      {"--roi camera:0,0,0,1,1,nan", "--roi"},
      {"--roi camera:0,0,0,1,1,inf", "--roi"},
      {"--roi box:0,0,0,1,1,1", "unknown frame 'box'"},
      {"--roi 0,0,0,1,1,1", "--roi"},
      {"--roi bin:0,0,0,1,1,1 --bin none", "needs --bin auto"},
      {"--bin maybe", "--bin 'maybe': expected none, auto, the interior size W,D,H"},
      {"--bin 600,400", "--bin"},
      {"--bin 600,0,300", "--bin"},
      {"--bin mesh:no_such_bin.stl", "--bin 'mesh:no_such_bin.stl': no_such_bin.stl"},
      {"--bin-margin -1", "--bin-margin -1 must be in [0, 10]"},
      {"--bin-margin nan", "--bin-margin"},
  };
  for (const Case& c : cases) {
    const auto r = test::run_binpick(base + c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << "\n" << r.err;
  }
  // The same through a --params file, named by the file and the key.
  const fs::path params = *dir_ / "bin_params.json";
  for (const auto& [json, message] : std::vector<std::pair<std::string, std::string>>{
           {R"({"bin": "sometimes"})", "bin_params.json: bin 'sometimes'"},
           {R"({"roi": 5})", "'roi' must be a string"},
           {R"({"roi": "camera:0,0,0,1,1,0"})", "bin_params.json: roi"},
           {R"({"bin_margin": "big"})", "must be a number"}}) {
    { std::ofstream(params) << json; }
    const auto r = test::run_binpick(base + "--params " + params.string());
    EXPECT_EQ(r.status, 2) << json << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << json << "\n" << r.err;
  }
  // A bracket over a floor: no bin. `auto` (the default) says so in --verbose and in the
  // summary, without a warning; a bin of a given size that is not there: one warning for the
  // three images. Results as usual.
  auto r = test::run_binpick(base + "--bin auto --hypotheses 2 --verbose");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("warning: no bin found"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("bin: not found"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("a bin found in 0 of 3 images"), std::string::npos) << r.out;
  EXPECT_FALSE(bop::read_results_csv(out).empty());
  r = test::run_binpick(base + "--bin 600,400,300 --hypotheses 2");
  ASSERT_EQ(r.status, 0) << r.err;
  std::size_t warnings = 0;
  for (std::size_t at = 0; (at = r.err.find("warning: no bin found", at)) != std::string::npos; ++at)
    ++warnings;
  EXPECT_EQ(warnings, 1u) << r.err;
  // A camera-frame ROI that leaves only the part's neighbourhood: --verbose says what it kept.
  r = test::run_binpick(base + "--roi camera:-100,-100,500,100,100,640 --hypotheses 2 --verbose");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("pixels with depth may be used"), std::string::npos) << r.out;
}

TEST(ResultsCsv, RoundTripsAndValidates) {
  const auto dir = test::fresh_temp_dir("results_csv");
  bop::ResultRow a;
  a.scene_id = 3;
  a.score = 812;
  a.R = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  a.t = {1.5, -2.25, 700.125};
  a.time = 0.413;
  bop::ResultRow b = a;
  b.im_id = 1, b.obj_id = 2, b.score = 7.5;
  bop::write_results_csv(dir / "r.csv", {a, b});
  const auto rows = bop::read_results_csv(dir / "r.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].R, a.R);  // shortest round-trip numbers: exact
  EXPECT_EQ(rows[0].t, a.t);
  EXPECT_EQ(rows[1].obj_id, 2);
  EXPECT_EQ(rows[1].score, 7.5);
  EXPECT_EQ(bop::format_results_csv({a, b}), test::slurp(dir / "r.csv"));
  const std::string h = "scene_id,im_id,obj_id,score,R,t,time\n";
  EXPECT_EQ(bop::parse_results_csv(h + "0,0,1,5,1 0 0 0 1 0 0 0 1,1 2 3,0.5\r\n\n", "x").size(), 1u);
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"", "empty"},
      {"scene,im\n", "line 1: expected the header"},
      {h + "0,0,1,5,1 0 0 0 1 0 0 0 1,1 2 3\n", "line 2: expected 7 columns"},
      {h + "0,0,1,5,1 0 0 0 1 0 0 0,1 2 3,0.5\n", "R needs 9"},
      {h + "0,0,1,5,1 0 0 0 1 0 0 0 1,1 2,0.5\n", "t needs 3"},
      {h + "0,0,1,5,1 0 0 0 1 0 0 0 1,1 2 nan,0.5\n", "line 2: t"},
      {h + "0,0,1,inf,1 0 0 0 1 0 0 0 1,1 2 3,0.5\n", "score"},
      {h + "0,0.5,1,5,1 0 0 0 1 0 0 0 1,1 2 3,0.5\n", "im_id"},
  };
  for (const auto& [text, message] : bad) {
    try {
      bop::parse_results_csv(text, "f.csv");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("f.csv"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(bop::read_results_csv(dir / "missing.csv"), InputError);
}

// A fixed cell's bin: found once and saved (--save-bin-pose), then given (--bin-pose) to every
// image; refused where it cannot apply, one clear message each.
TEST_F(DetectCli, BinPoseIsSavedOnceAndGivenToEveryImage) {
  // Two images of an analytic bin (bin_scene.hpp), tilted and turned, as a BOP dataset.
  test::BinSceneSpec spec;
  spec.tilt_deg = 20, spec.yaw_deg = 25;
  const test::BinScene scene = test::make_bin_scene(spec);
  const fs::path data = *dir_ / "bin_data";
  const bp_camera& c = scene.cam;
  fs::create_directories(data);
  bop::write_camera(data / "camera.json", {c.fx, c.fy, c.cx, c.cy, c.width, c.height, c.depth_scale});
  for (int s = 0; s < 2; ++s) {
    const fs::path sd = data / "test" / fmt::format("{:06d}", s);
    fs::create_directories(sd / "depth");
    write_png(sd / "depth" / "000000.png", GrayImage<std::uint16_t>{c.width, c.height, scene.depth.raw});
    bop::SceneCamera cam;
    cam.K << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1;
    cam.depth_scale = c.depth_scale;
    bop::write_scene_cameras(sd / "scene_camera.json", {{0, cam}});
  }
  const fs::path pose = *dir_ / "cell_bin.json", out = *dir_ / "bin_pose.csv";
  const std::string base = fmt::format("detect --model {} --dataset {} --out {} --hypotheses 1 "
                                       "--more-hypotheses 0 ", model_, data.string(), out.string());
  auto r = test::run_binpick(base + "--bin 400,300,180 --save-bin-pose " + pose.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("wrote the bin of scene 0 image 0"), std::string::npos) << r.out;
  const BinSpec saved = read_bin_pose(pose);
  EXPECT_LT(test::angle_deg(saved.R.col(2), scene.bin_to_cam.col(2)), 1.0);
  EXPECT_LT(scene.to_bin(saved.t).norm(), 5.0);
  EXPECT_EQ(saved.size, Eigen::Vector3d(400, 300, 180));

  fs::remove(out);
  r = test::run_binpick(base + "--bin-pose " + pose.string() + " --verbose");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("bin: given (--bin-pose)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("a bin found in 2 of 2 images"), std::string::npos) << r.out;
  // A rerun with the same file resumes; with the file edited it is another run (its bytes are in
  // the batch's fingerprint, not only its name).
  r = test::run_binpick(base + "--bin-pose " + pose.string());
  EXPECT_NE(r.out.find("(2 done before)"), std::string::npos) << r.out;
  {
    nlohmann::json j = nlohmann::json::parse(test::slurp(pose));
    j["interior_mm"][0] = 410.0;
    std::ofstream(pose) << j.dump();
  }
  r = test::run_binpick(base + "--bin-pose " + pose.string());
  EXPECT_NE(r.out.find("(0 done before)"), std::string::npos) << r.out;

  // Refused: no bin in any image (nothing written), options it does not go with, a bad file.
  const fs::path nowhere = *dir_ / "no_bin.json";
  r = test::run_binpick(fmt::format("detect --model {} --dataset {} --out {} --save-bin-pose {}",
                                    model_, (*dir_ / "data").string(), (*dir_ / "nb.csv").string(),
                                    nowhere.string()));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--save-bin-pose: no bin was found"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(nowhere));
  const fs::path bad = *dir_ / "bad_bin.json";
  { std::ofstream(bad) << R"({"cam_R_bin": [1,0,0,0,1,0,0,0,1], "cam_t_bin": [0,0,1]})"; }
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"--bin-pose " + (*dir_ / "missing.json").string(), "missing.json"},
           {"--bin-pose " + bad.string(), "bad_bin.json: \"interior_mm\" is missing"},
           {"--bin none --save-bin-pose " + nowhere.string(), "it needs --bin auto or --bin W,D,H"},
           {"--bin-pose " + pose.string() + " --save-bin-pose " + nowhere.string(), "not --bin none or --bin-pose"},
           {"--shard 1/2 --save-bin-pose " + nowhere.string(), "not with --shard or --slurm"}}) {
    r = test::run_binpick(base + args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
  }
}
