// The report of `binpick eval`: files written and non-empty, pictures that show what they say,
// datasets ordered and labelled by noise, the score calibration (and a warning, not a plot, for
// results that hold vote counts), on a small hand-made dataset (no rendering needed).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/eval/eval_run.hpp"
#include "host/eval/report/gnuplot.hpp"
#include "host/eval/report/precision_plot.hpp"
#include "host/eval/report/pick_picture.hpp"
#include "host/eval/report/scene_pictures.hpp"
#include "host/formats/bop/bop_models.hpp"
#include "host/app/options/model_options.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "tests/support/cli_run.hpp"

namespace binpick::eval {
namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kW = 320, kH = 240;
constexpr double kF = 400, kScale = 0.1;  // focal (px), depth scale (mm per unit)

std::vector<bop::GroundTruth> toy_parts() {
  return {{1, {Eigen::Matrix3d::Identity(), {-60, 0, 800}}},
          {1, {Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitY()).toRotationMatrix(), {60, 20, 820}}}};
}

// One bin of two parts over a floor at 900 mm: a bump of depth around each part, no data in a
// corner, an intensity gradient. noise < 0 writes no synth.json.
void write_toy_dataset(const fs::path& root, double noise) {
  fs::create_directories(root / "test/000000/depth");
  fs::create_directories(root / "test/000000/gray");
  bop::write_camera(root / "camera.json", {kF, kF, kW / 2.0, kH / 2.0, kW, kH, kScale});
  write_bop_models(root, cli::load_part({"builtin:bracket", {}}).mesh, 1, {});
  const auto parts = toy_parts();
  bop::write_scene_gt(root / "test/000000/scene_gt.json", {{0, parts}});
  bop::SceneCamera cam;
  cam.K << kF, 0, kW / 2.0, 0, kF, kH / 2.0, 0, 0, 1;
  cam.depth_scale = kScale;
  bop::write_scene_cameras(root / "test/000000/scene_camera.json", {{0, cam}});
  GrayImage<std::uint16_t> depth{kW, kH, std::vector<std::uint16_t>(kW * kH)};
  GrayImage<std::uint8_t> gray{kW, kH, std::vector<std::uint8_t>(kW * kH)};
  for (std::uint32_t y = 0; y < kH; ++y)
    for (std::uint32_t x = 0; x < kW; ++x) {
      double z = 900;
      for (const auto& p : parts) {
        const double u = kF * p.model_to_camera.t.x() / p.model_to_camera.t.z() + kW / 2.0;
        const double v = kF * p.model_to_camera.t.y() / p.model_to_camera.t.z() + kH / 2.0;
        const double r2 = (x - u) * (x - u) + (y - v) * (y - v);
        z = std::min(z, p.model_to_camera.t.z() + 80 * (1 - std::exp(-r2 / 800.0)));
      }
      const bool hole = x < 20 && y < 20;
      depth.pixels[y * kW + x] = hole ? 0 : std::uint16_t(z / kScale);
      gray.pixels[y * kW + x] = std::uint8_t(60 + (x * 120) / kW + (hole ? 0 : 40 * (z < 880)));
    }
  write_png(root / "test/000000/depth/000000.png", depth);
  write_png(root / "test/000000/gray/000000.png", gray);
  if (noise >= 0) {
    std::ofstream(root / "synth.json") << nlohmann::json{{"noise", noise}}.dump() << "\n";
  }
}

// A correct top hypothesis, one 20 degrees off and one 15 mm off; verified scores (in [0, 1]).
std::vector<bop::ResultRow> toy_results() {
  const auto parts = toy_parts();
  std::vector<bop::ResultRow> rows(3);
  rows[0].score = 0.9;
  rows[0].R = parts[0].model_to_camera.R, rows[0].t = parts[0].model_to_camera.t;
  rows[1].score = 0.5;
  rows[1].R = parts[1].model_to_camera.R * Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitX()).toRotationMatrix();
  rows[1].t = parts[1].model_to_camera.t;
  rows[2].score = 0.3, rows[2].t = parts[1].model_to_camera.t + Eigen::Vector3d(15, 0, 0);
  rows[2].R = parts[1].model_to_camera.R;
  for (auto& r : rows) r.time = 0.3;
  return rows;
}

bool non_empty(const fs::path& p) { return fs::is_regular_file(p) && fs::file_size(p) > 0; }

TEST(EvalReport, WritesEveryFileAndReferencesThem) {
  const fs::path dir = test::fresh_temp_dir("eval_report");
  write_toy_dataset(dir / "ds", -1);
  bop::write_results_csv(dir / "ds.csv", toy_results());
  ReportOptions options;
  options.out = dir / "report";
  options.pictures = 1;
  const auto evaluations = evaluate_inputs({{dir / "ds", dir / "ds.csv", {}}}, options.eval);
  ASSERT_EQ(evaluations.size(), 1u);
  EXPECT_EQ(evaluations[0].dataset.label, "ds");
  EXPECT_NEAR(evaluations[0].summary.loose.top, 1.0, 1e-12);
  EXPECT_NEAR(evaluations[0].summary.loose.all, 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(evaluations[0].summary.ms_per_hypothesis, 100.0, 1e-9);

  // The one right pose scores 0.9: the threshold keeping it accepts nothing wrong.
  const ScoreCalibration& c = evaluations[0].summary.score_loose;
  EXPECT_DOUBLE_EQ(c.threshold, 0.9);
  EXPECT_EQ(c.accepted, 1u);
  EXPECT_DOUBLE_EQ(c.wrong_fraction, 0.0);

  const ReportFiles files = write_report(evaluations, options);
  for (const auto& f :
       {files.html, files.json, files.curves_csv, files.score_curves_csv, files.hypotheses_csv})
    EXPECT_TRUE(non_empty(f)) << f;
  EXPECT_EQ(files.score_curves_csv, options.out / "score_curves.csv");
  EXPECT_TRUE(files.warnings.empty()) << (files.warnings.empty() ? "" : files.warnings.front());
  const std::string html = test::slurp(files.html);
  const bool have_gnuplot = find_gnuplot().has_value();
  EXPECT_TRUE(have_gnuplot) << "gnuplot (Debian gnuplot-nox) draws the precision plot";
  if (have_gnuplot) {
    EXPECT_TRUE(non_empty(options.out / "precision.png"));
    EXPECT_NE(html.find("src=\"precision.png\""), std::string::npos);
    EXPECT_EQ(files.score_plot, options.out / "score_threshold.png");
    EXPECT_TRUE(non_empty(options.out / "score_threshold.png"));
    EXPECT_NE(html.find("src=\"score_threshold.png\""), std::string::npos);
  }
  // The score section, its table and the summary's columns; the wording of a ranked score.
  EXPECT_NE(html.find("<h2>Precision against score threshold</h2>"), std::string::npos);
  EXPECT_NE(html.find("href=\"score_curves.csv\""), std::string::npos);
  EXPECT_NE(html.find("score threshold keeping<br>90 % of right poses"), std::string::npos);
  EXPECT_NE(html.find("<td>0.9</td><td>0.0 % (0 of 1)</td></tr>"), std::string::npos) << html;
  EXPECT_NE(html.find("top-ranked"), std::string::npos);
  EXPECT_EQ(html.find("top-voted"), std::string::npos);
  EXPECT_EQ(html.find("votes"), std::string::npos);
  for (const char* kind : {"depth", "intensity", "hypotheses", "detections", "closeup"}) {
    const std::string rel = std::string("pictures/d0_000000_000000_") + kind + ".png";
    EXPECT_TRUE(non_empty(options.out / rel)) << rel;
    EXPECT_NE(html.find("src=\"" + rel + "\""), std::string::npos) << rel;
  }
  const auto json = nlohmann::json::parse(test::slurp(files.json));
  EXPECT_DOUBLE_EQ(json["datasets"][0]["precision"]["loose"]["top"].get<double>(), 1.0);
  EXPECT_EQ(json["datasets"][0]["hypotheses"].get<int>(), 3);
  EXPECT_DOUBLE_EQ(json["operating_points"]["strict"]["rotation_deg"].get<double>(), 5.0);
  const auto& calibration = json["datasets"][0]["score_calibration"];
  EXPECT_DOUBLE_EQ(calibration["keep"].get<double>(), 0.9);
  EXPECT_EQ(calibration["scores_outside_unit"].get<int>(), 0);
  EXPECT_DOUBLE_EQ(calibration["loose"]["threshold"].get<double>(), 0.9);
  EXPECT_EQ(calibration["loose"]["accepted_wrong"].get<int>(), 0);
  EXPECT_EQ(calibration["loose"]["right"].get<int>(), 1);
  EXPECT_TRUE(calibration["strict"]["any_right"].get<bool>());
  const std::string score_curves = test::slurp(files.score_curves_csv);
  EXPECT_EQ(score_curves.rfind("label,threshold,accepted,precision,kept\n", 0), 0u);
  // At 0.5: the right pose (0.9) and the one 20 degrees off (0.5); above 0.9 nothing.
  EXPECT_NE(score_curves.find("\n\"ds\",0.5,2,0.5,1\n"), std::string::npos) << score_curves;
  EXPECT_NE(score_curves.find("\n\"ds\",0.91,0,1,0\n"), std::string::npos) << score_curves;
  const std::string curves = test::slurp(files.curves_csv);
  EXPECT_EQ(curves.rfind("label,set,error,threshold,precision\n", 0), 0u);
  EXPECT_NE(curves.find("\"ds\",top,rotation_deg,60,1\n"), std::string::npos);
  // No temporary file of the atomic writes or of gnuplot is left behind.
  for (const auto& entry : fs::recursive_directory_iterator(options.out))
    EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
}

// Results of an older detect (vote counts): a warning in the report, no score plot, the
// numbers still written and flagged.
TEST(EvalReport, VoteCountScoresAreAWarningNotAPlot) {
  const fs::path dir = test::fresh_temp_dir("eval_report_votes");
  write_toy_dataset(dir / "ds", -1);
  auto rows = toy_results();
  rows[0].score = 900, rows[1].score = 500, rows[2].score = 300;
  bop::write_results_csv(dir / "ds.csv", rows);
  ReportOptions options;
  options.out = dir / "report";
  options.pictures = 0;
  const auto evaluations = evaluate_inputs({{dir / "ds", dir / "ds.csv", {}}}, options.eval);
  const ReportFiles files = write_report(evaluations, options);
  ASSERT_FALSE(files.warnings.empty());
  EXPECT_EQ(files.warnings[0].rfind("ds: 3 of 3 scores are outside [0, 1] (highest 900)", 0), 0u)
      << files.warnings[0];
  EXPECT_TRUE(files.score_plot.empty());
  EXPECT_FALSE(fs::exists(options.out / "score_threshold.png"));
  const std::string html = test::slurp(files.html);
  EXPECT_NE(html.find("3 of 3 scores are outside [0, 1]"), std::string::npos);
  EXPECT_NE(html.find("900 <span class=\"warn\">(scores not in [0, 1])</span>"), std::string::npos)
      << html;
  EXPECT_EQ(html.find("src=\"score_threshold.png\""), std::string::npos);
  const auto json = nlohmann::json::parse(test::slurp(files.json));
  EXPECT_EQ(json["datasets"][0]["score_calibration"]["scores_outside_unit"].get<int>(), 3);
  EXPECT_DOUBLE_EQ(json["datasets"][0]["score_calibration"]["max_score"].get<double>(), 900);
}

TEST(EvalReport, CurvesAreOrderedAndLabelledByNoise) {
  const fs::path dir = test::fresh_temp_dir("eval_report_noise");
  write_toy_dataset(dir / "noisy", 0.03);
  write_toy_dataset(dir / "clean", 0.0);
  bop::write_results_csv(dir / "r.csv", toy_results());
  const auto evaluations =
      evaluate_inputs({{dir / "noisy", dir / "r.csv", {}}, {dir / "clean", dir / "r.csv", {}}});
  ASSERT_EQ(evaluations.size(), 2u);
  EXPECT_EQ(evaluations[0].dataset.label, "sigma 0 % of d");
  EXPECT_EQ(evaluations[1].dataset.label, "sigma 3 % of d");
  std::vector<LabelledCurves> curves;
  for (const auto& e : evaluations) curves.push_back({e.dataset.label, e.curves});
  const std::string script = figure7_script(curves);
  EXPECT_NE(script.find("'sigma 3 % of d'"), std::string::npos);
  EXPECT_NE(script.find("multiplot layout 2,2"), std::string::npos);
}

// BOP's industrial layout: another split, the sensor's suffix on every file, an image id other
// than 0 and a colour rgb/ image instead of gray/.
TEST(EvalDataset, ReadsSensorSuffixesOtherSplitsAndRgb) {
  const fs::path dir = test::fresh_temp_dir("eval_sensor_layout");
  write_toy_dataset(dir / "plain", -1);
  const fs::path root = dir / "ds", scene = root / "val/000004";
  fs::create_directories(scene / "depth_photoneo");
  fs::create_directories(scene / "rgb_photoneo");
  fs::copy(dir / "plain/models", root / "models");
  const fs::path plain = dir / "plain/test/000000";
  bop::write_scene_gt(scene / "scene_gt_photoneo.json",
                      {{7, bop::read_scene_gt(plain / "scene_gt.json").at(0)}});
  bop::write_scene_cameras(scene / "scene_camera_photoneo.json",
                           {{7, bop::read_scene_cameras(plain / "scene_camera.json").at(0)}});
  fs::copy(plain / "depth/000000.png", scene / "depth_photoneo/000007.png");
  const auto gray = read_png8(plain / "gray/000000.png");
  RgbImage rgb{gray.width, gray.height, {}};
  for (auto g : gray.pixels) rgb.pixels.insert(rgb.pixels.end(), {g, g, g});
  write_png(scene / "rgb_photoneo/000007.png", rgb);

  const Dataset d = load_dataset(root, {"val", "photoneo"});
  ASSERT_EQ(d.images.size(), 1u);
  ASSERT_TRUE(d.images.count({4, 7}));
  EXPECT_EQ(d.images.at({4, 7}).gt.size(), toy_parts().size());
  const SceneView view = load_scene_view(d, {4, 7});
  ASSERT_EQ(view.gray.pixels.size(), gray.pixels.size());
  for (std::size_t i = 0; i < gray.pixels.size(); i += 97)
    EXPECT_NEAR(int(view.gray.pixels[i]), int(gray.pixels[i]), 1) << i;

  // Without the sensor, or with a name that is not a file suffix, one clear message.
  try {
    load_dataset(root, {"val", ""});
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no scene with a scene_gt.json under val/"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(load_dataset(root, {"val", "../x"}), InputError);
  EXPECT_THROW(load_dataset(root, {"test", "photoneo"}), InputError);
}

TEST(EvalPictures, DepthIsDarkNearAndBlackWithoutData) {
  const fs::path dir = test::fresh_temp_dir("eval_pictures");
  write_toy_dataset(dir / "ds", -1);
  const Dataset d = load_dataset(dir / "ds");
  const SceneView view = load_scene_view(d, {0, 0});
  DepthRange range;
  const Canvas depth = depth_false_colour(view, &range);
  EXPECT_LT(range.near_mm, range.far_mm);
  auto brightness = [](Rgb c) { return int(c[0]) + c[1] + c[2]; };
  EXPECT_EQ(brightness(depth.get(5, 5)), 0);  // the hole
  // The first part's centre (near) is darker than the floor (far).
  const auto centre = view.project({-60, 0, 800});
  ASSERT_TRUE(centre);
  EXPECT_LT(brightness(depth.get(int(centre->x()), int(centre->y()))), brightness(depth.get(300, 230)));

  // The hypotheses picture colours the neighbourhood of the first hypothesis in its rank colour.
  const auto rows = toy_results();
  HypothesisResult h;
  h.row = rows[0];
  h.top = true;
  const Canvas hyps = hypotheses_picture(view, {&h}, 40.0);
  const Rgb near = hyps.get(int(centre->x()) + 12, int(centre->y()) + 2);
  EXPECT_GT(near[0], near[2]) << "rank 1 is orange";
  // Far away from it the picture is the dimmed intensity image: grey.
  const Rgb far = hyps.get(300, 230);
  EXPECT_EQ(far[0], far[2]);
}

// Pixels clearly of one colour: green (a succeeding pick) or red (a failing one).
std::pair<int, int> green_and_red(const Canvas& c) {
  int green = 0, red = 0;
  for (std::uint32_t y = 0; y < c.height(); ++y)
    for (std::uint32_t x = 0; x < c.width(); ++x) {
      const Rgb p = c.get(int(x), int(y));
      green += p[1] > p[0] + 60 && p[1] > p[2] + 60;
      red += p[0] > p[1] + 60 && p[0] > p[2] + 60;
    }
  return {green, red};
}

TEST(EvalPictures, APickIsItsGripperGreenWhereItSucceedsRedWhereItFails) {
  const fs::path dir = test::fresh_temp_dir("eval_pick_picture");
  write_toy_dataset(dir / "ds", -1);
  const Dataset d = load_dataset(dir / "ds");
  const SceneView view = load_scene_view(d, {0, 0});
  PickOutcome o;
  o.pick.grasp.translation() = Eigen::Vector3d(-60, 0, 780);  // down onto the first part
  o.pick.gripper = "suction:20,10,20,100";
  o.right = o.on_grasp = true;
  const Canvas good = picks_picture(view, {&o}, {}, {}, 100.0);
  // A crop around the pick (three diameters at 780 mm: ~150 pixels), magnified.
  EXPECT_GE(good.width(), 400u);
  EXPECT_LE(good.width(), 700u);
  const auto [green, red] = green_and_red(good);
  EXPECT_GT(green, 200);  // the cup's footprint (~20 mm across: ~10 pixels, magnified) and outline
  EXPECT_EQ(red, 0);
  o.collision = "part 1 (obj_id 1)";
  EXPECT_EQ(o.verdict(), "hits part 1 (obj_id 1)");
  const auto [green2, red2] = green_and_red(picks_picture(view, {&o}, {}, {}, 100.0));
  EXPECT_EQ(green2, 0);
  EXPECT_EQ(red2, green);  // the same drawing in the other colour
  // A pick behind the camera draws nothing and shows the whole image.
  o.pick.grasp.translation() = Eigen::Vector3d(0, 0, -100);
  const Canvas none = picks_picture(view, {&o}, {}, {}, 100.0);
  EXPECT_EQ(none.width(), kW * 2);
  EXPECT_EQ(green_and_red(none), std::make_pair(0, 0));
}

}  // namespace
}  // namespace binpick::eval
