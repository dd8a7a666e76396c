// Detection with the bin left out (--bin, --roi) and with missing depth, on analytic bins
// (bin_scene.hpp) and the L-bracket's model: no hypothesis on the bin's rim or walls, straight
// down and tilted; a region that keeps every pixel changes nothing; an image with 70 % of its
// pixels lost in blobs and stripes runs through, and a crop with too little depth is skipped with
// its reason instead of voting.
#include <gtest/gtest.h>

#include <memory>

#include "host/detect/verify/score.hpp"
#include "host/core/error.hpp"
#include "host/detect/batch/detect_batch.hpp"
#include "host/detect/detector.hpp"
#include "host/train/ppf_model.hpp"
#include "tests/detect/bin/bin_scene.hpp"
#include "tests/support/test_meshes.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

const PpfModel& bracket() {
  static const std::unique_ptr<PpfModel> model =
      std::make_unique<PpfModel>(train_ppf_model(l_bracket(), {}));
  return *model;
}

// Without a region (the paper's setting); each test asks for the bin or ROI it is about.
DetectParams fast_params() {
  DetectParams p;
  p.bin = "none";
  p.ref_ratio = 0.05;
  p.hypotheses = 4;
  p.refine_iterations = 2;
  p.candidates = 2;
  return p;
}

bool on_bin(const BinScene& scene, const BinSceneSpec& s, const Hypothesis& h) {
  const Eigen::Vector3d q = scene.to_bin(h.point.cast<double>());
  return std::abs(q.x()) > s.W / 2 - 2 || std::abs(q.y()) > s.D / 2 - 2 || q.z() > s.H - 2;
}

}  // namespace

TEST(DetectBin, NoHypothesisOnTheBin) {
  for (double tilt : {0.0, 20.0}) {
    SCOPED_TRACE(testing::Message() << "tilt " << tilt);
    BinSceneSpec s;
    s.tilt_deg = tilt;
    const BinScene scene = make_bin_scene(s);
    {
      Detector bare(bracket(), fast_params());
      const auto found = bare.detect(scene.depth, scene.cam);
      std::size_t on = 0;
      for (const Detection& d : found) on += on_bin(scene, s, d.hypothesis);
      for (const Detection& d : bare.skipped()) on += on_bin(scene, s, d.hypothesis);
      EXPECT_GT(on, 0u) << "without --bin the rim should draw hypotheses (the test's premise)";
      EXPECT_TRUE(bare.region_report().empty());
    }
    DetectParams p = fast_params();
    p.bin = "auto";
    Detector det(bracket(), p);
    const auto found = det.detect(scene.depth, scene.cam);
    EXPECT_FALSE(found.empty());
    for (const Detection& d : found)
      EXPECT_FALSE(on_bin(scene, s, d.hypothesis)) << d.hypothesis.point.transpose();
    for (const Detection& d : det.skipped())
      EXPECT_FALSE(on_bin(scene, s, d.hypothesis)) << d.hypothesis.point.transpose();
    EXPECT_NE(det.region_report().find("bin: interior"), std::string::npos) << det.region_report();
    EXPECT_NE(det.region_report().find("excluded"), std::string::npos) << det.region_report();
    // The same with the size given, and with a bin-frame ROI over the interior's left half.
    p.bin = "400,300,180";
    p.roi = "bin:-200,-150,-10,0,150,300";
    Detector sized(bracket(), p);
    for (const Detection& d : sized.detect(scene.depth, scene.cam)) {
      EXPECT_FALSE(on_bin(scene, s, d.hypothesis));
      EXPECT_LT(scene.to_bin(d.hypothesis.point.cast<double>()).x(), 2.0);
    }
  }
}

// A camera-frame ROI holding every point: the mask keeps every pixel with depth, and the
// detections are those of no ROI, field for field.
TEST(DetectBin, RegionKeepingEverythingChangesNothing) {
  const BinScene scene = make_bin_scene({});
  Detector bare(bracket(), fast_params());
  DetectParams p = fast_params();
  p.roi = "camera:-5000,-5000,0,5000,5000,5000";
  Detector boxed(bracket(), p);
  const auto a = bare.detect(scene.depth, scene.cam);
  const auto b = boxed.detect(scene.depth, scene.cam);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].hypothesis.pixel, b[i].hypothesis.pixel);
    EXPECT_EQ(a[i].R, b[i].R);
    EXPECT_EQ(a[i].t, b[i].t);
    EXPECT_EQ(a[i].votes, b[i].votes);
    EXPECT_EQ(a[i].score(), b[i].score());
  }
  EXPECT_NE(boxed.region_report().find("(0 excluded)"), std::string::npos) << boxed.region_report();
}

// 70 % of the pixels lost, plus specks of depth high above the bin (stray pixels, a wire): the
// specks become the highest points, their crops hold a handful of points and are skipped with a
// reason; the rest is detected as usual. With --bin auto the specks are outside the bin.
TEST(DetectBin, LargeHolesAndSpecksAreSkippedWithAReason) {
  BinSceneSpec s;
  s.tilt_deg = 10;
  BinScene scene = make_bin_scene(s);
  punch_holes(scene.depth, 0.7, 11);
  const std::size_t holes = std::size_t(std::count(scene.depth.raw.begin(), scene.depth.raw.end(), 0));
  EXPECT_GE(holes, std::size_t(0.7 * scene.depth.raw.size()));
  // Each speck in a shadow of its own, so that its low-pass depth is its own.
  for (auto [u, v] : {std::pair{100u, 100u}, {220u, 150u}}) {
    for (std::uint32_t y = v - 8; y <= v + 8; ++y)
      for (std::uint32_t x = u - 8; x <= u + 10; ++x) scene.depth.raw[std::size_t(y) * scene.cam.width + x] = 0;
    for (std::uint32_t k = 0; k < 3; ++k)
      scene.depth.raw[std::size_t(v) * scene.cam.width + u + k] = std::uint16_t(5000 + 10 * k);
  }
  DetectParams p = fast_params();
  p.hypotheses = 6;
  Detector det(bracket(), p);
  std::vector<Detection> found;
  ASSERT_NO_THROW(found = det.detect(scene.depth, scene.cam));
  EXPECT_FALSE(found.empty());
  ASSERT_EQ(det.skipped().size(), 2u);
  for (const Detection& d : det.skipped()) {
    EXPECT_LE(d.index, 1u) << "the specks are the highest points";
    EXPECT_EQ(d.votes, 0u);
    EXPECT_EQ(d.score(), 0.0);
    EXPECT_NE(d.reason.find("skipped: the crop has 3 points with depth"), std::string::npos)
        << d.reason;
  }
  for (const Detection& d : found) EXPECT_GE(d.index, 2u);
  // In the details file: after the image's rows, rank empty, the reason quoted.
  const std::string rows = skipped_rows(det.skipped(), 7, 0);
  EXPECT_TRUE(rows.starts_with("7,0,,0,0,0.000000,0,0,0" + std::string(kScoreFactorCount, ',') +
                               ",\"skipped: the crop has 3 points"))
      << rows;
  EXPECT_EQ(std::count(rows.begin(), rows.end(), '\n'), 2);
  // The bin is still found through the holes, and the specks (500 mm over the floor) are out.
  DetectParams pb = p;
  pb.bin = "auto";
  Detector in_bin(bracket(), pb);
  ASSERT_NO_THROW(found = in_bin.detect(scene.depth, scene.cam));
  EXPECT_NE(in_bin.region_report().find("bin: interior"), std::string::npos)
      << in_bin.region_report();
  EXPECT_TRUE(in_bin.skipped().empty());
  for (const Detection& d : found) EXPECT_FALSE(on_bin(scene, s, d.hypothesis));
}

// Nothing but holes and one speck: every hypothesis is skipped, none crashes.
TEST(DetectBin, OnlySpecksGiveNoDetectionAndNoCrash) {
  const bp_camera cam{520.0f, 520.0f, 159.5f, 119.5f, 0.1f, 320, 240, 0};
  DepthImage depth{320, 240, std::vector<std::uint16_t>(320 * 240, 0)};
  depth.raw[120 * 320 + 160] = 9000;
  depth.raw[10 * 320 + 10] = 9500;
  Detector det(bracket(), fast_params());
  std::vector<Detection> found;
  ASSERT_NO_THROW(found = det.detect(depth, cam));
  EXPECT_TRUE(found.empty());
  EXPECT_EQ(det.skipped().size(), 2u);
  // The bin asked for and not there: said once (stderr), the whole image used.
  DetectParams p = fast_params();
  p.bin = "auto";
  Detector no_bin(bracket(), p);
  ASSERT_NO_THROW(found = no_bin.detect(depth, cam));
  EXPECT_NE(no_bin.region_report().find("not found"), std::string::npos) << no_bin.region_report();
  EXPECT_EQ(no_bin.skipped().size(), 2u);
}

// The last parts of a bin of sheet metal lie flat on its floor, thinner (1.5 mm) than the floor
// fit's tolerance (3 mm here): the floor's clearance is capped at half the part's thinnest
// extent, so the sheets stay in the region and are found. A thick part's clearance keeps the
// whole tolerance, which would have left the sheets out with the floor (the test's premise).
TEST(DetectBin, SheetsLyingOnTheFloorStayInTheRegion) {
  const Eigen::Vector3f size(120.0f, 80.0f, 1.5f);
  const PpfModel sheet = train_ppf_model(box(size), {});
  BinSceneSpec s;
  s.spheres.clear();
  const std::vector<Eigen::Vector2d> centres = {{-90, -60}, {80, 50}};
  for (const Eigen::Vector2d& c : centres)
    s.boxes.push_back({Eigen::Vector3d(c.x() - 60, c.y() - 40, 0),
                       Eigen::Vector3d(c.x() + 60, c.y() + 40, 1.5)});
  const BinScene scene = make_bin_scene(s);
  const auto kept = [](const std::string& report) {
    const std::size_t at = report.find("mask: ");
    return at == std::string::npos ? 0ul : std::stoul(report.substr(at + 6));
  };
  DetectParams p = fast_params();
  p.bin = "auto";
  p.hypotheses = 2;
  p.more_hypotheses = 0;
  {
    Detector thick(bracket(), p);
    (void)thick.detect(scene.depth, scene.cam);
    EXPECT_LT(kept(thick.region_report()), 100u) << thick.region_report();
  }
  Detector det(sheet, p);
  const std::vector<Detection> found = det.detect(scene.depth, scene.cam);
  // Each sheet shows about 63 x 42 pixels at 1 m.
  EXPECT_GT(kept(det.region_report()), 4000u) << det.region_report();
  ASSERT_EQ(found.size(), 2u);
  for (const Detection& d : found) {
    const Eigen::Vector3d c = scene.to_bin(d.R * (0.5 * size.cast<double>()) + d.t);
    double nearest = 1e9;
    for (const Eigen::Vector2d& want : centres)
      nearest = std::min(nearest, (c - Eigen::Vector3d(want.x(), want.y(), 0.75)).norm());
    EXPECT_LT(nearest, 0.1 * sheet.diameter) << c.transpose();
    // The edge step scales it by the step down at the edges: 1.5 mm of a 5.8 mm tolerance.
    EXPECT_GT(d.score(), 0.15);
  }
}

namespace {

// Whether a point (camera frame) of the scene is seen through its -y wall below the rim.
bool behind_near_wall(const BinScene& scene, const BinSceneSpec& s, const Eigen::Vector3d& p) {
  const Eigen::Vector3d c = scene.to_bin(Eigen::Vector3d::Zero()), q = scene.to_bin(p);
  const double at = -s.D / 2;
  if (!(c.y() < at && q.y() >= at)) return false;
  const double f = (at - c.y()) / (q.y() - c.y());
  return c.z() + f * (q.z() - c.z()) < s.H;
}

}  // namespace

// A bin whose near wall is bars, seen by a camera tilted 35 degrees beyond it: the parts lying
// along that wall are nearest the camera, seen between the bars. Kept in (--through-walls)
// they draw the first hypotheses; by default none lies behind the wall.
TEST(DetectBin, NoHypothesisBehindAMeshWall) {
  BinSceneSpec s;
  s.tilt_deg = 35;
  s.bars_my = 24;
  s.spheres = {{-60, -120, 25, 25}, {70, -115, 22, 22}, {-100, 40, 25, 25}, {90, 60, 25, 25}};
  const BinScene scene = make_bin_scene(s);
  DetectParams p = fast_params();
  p.bin = "auto";
  p.through_walls = 1;
  Detector kept(bracket(), p);
  std::size_t behind = 0;
  for (const Detection& d : kept.detect(scene.depth, scene.cam))
    behind += behind_near_wall(scene, s, d.hypothesis.point.cast<double>());
  EXPECT_NE(kept.region_report().find("bin: interior"), std::string::npos) << kept.region_report();
  EXPECT_GT(behind, 0u) << "the premise: without the test hypotheses lie behind the bars";
  p.through_walls = 0;
  Detector det(bracket(), p);
  const auto found = det.detect(scene.depth, scene.cam);
  EXPECT_FALSE(found.empty());
  for (const Detection& d : found)
    EXPECT_FALSE(behind_near_wall(scene, s, d.hypothesis.point.cast<double>()))
        << d.hypothesis.point.transpose();
  for (const Detection& d : det.skipped())
    EXPECT_FALSE(behind_near_wall(scene, s, d.hypothesis.point.cast<double>()));
  EXPECT_EQ(det.region_report().find("highest along"), std::string::npos);
  // Highest along the bin's up (--highest-up): said in the report, and still none behind.
  p.highest_up = 1;
  Detector up(bracket(), p);
  const auto along = up.detect(scene.depth, scene.cam);
  EXPECT_FALSE(along.empty());
  for (const Detection& d : along)
    EXPECT_FALSE(behind_near_wall(scene, s, d.hypothesis.point.cast<double>()));
  EXPECT_NE(up.region_report().find("highest along the bin's up"), std::string::npos)
      << up.region_report();
}
