// Pick success (host/eval/metrics/pick_success.hpp) on a hand-made scene: a 40 x 40 x 10 mm tile
// seen from above, a suction pick on its top; the same pick with another tile lying over it, off
// its grasp, on a wrong detection, against the bin's wall; and the picks file's reader.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "host/core/angles.hpp"
#include "host/core/error.hpp"
#include "host/eval/metrics/pick_success.hpp"
#include "host/app/options/model_options.hpp"
#include "host/core/gripper.hpp"
#include "host/train/ppf_model.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;
using namespace binpick::eval;

namespace {

// The tile's surface every mm, model frame: x, y in [-20, 20], z in [-5, 5] (top at z = -5,
// towards the camera, which looks along +z), normals out of the tile.
PointCloud tile_surface() {
  PointCloud out;
  for (float u = -20; u <= 20; u += 1) {
    for (float v = -20; v <= 20; v += 1)
      for (float z : {-5.0f, 5.0f}) {
        out.points.emplace_back(u, v, z);
        out.normals.emplace_back(0.0f, 0.0f, z < 0 ? -1.0f : 1.0f);
      }
    for (float z = -4; z <= 4; z += 1)  // the four sides
      for (float side : {-20.0f, 20.0f}) {
        out.points.emplace_back(side, u, z);
        out.normals.emplace_back(side / 20, 0.0f, 0.0f);
        out.points.emplace_back(u, side, z);
        out.normals.emplace_back(0.0f, side / 20, 0.0f);
      }
  }
  return out;
}

struct Scene {
  Dataset dataset;
  EvalSummary summary;
  PartSurfaces vertices;
};

// One tile at (0, 0, 600) (the pick's part), and `over` more tiles at the given positions.
Scene scene(const std::vector<Eigen::Vector3d>& over = {}) {
  Scene s;
  s.dataset.models[1].diameter = 58;
  EvalImage& image = s.dataset.images[{0, 0}];
  bop::GroundTruth gt;
  gt.model_to_camera.t = {0, 0, 600};
  image.gt.push_back(gt);
  for (const auto& t : over) {
    gt.model_to_camera.t = t;
    image.gt.push_back(gt);
  }
  // The bin: 200 x 200 x 100 interior, floor 5 mm under the tile, up towards the camera.
  image.camera.world_to_camera.R = Eigen::Vector3d(1, -1, -1).asDiagonal();
  image.camera.world_to_camera.t = {0, 0, 605};
  HypothesisResult h;
  h.gt_index = 0;
  h.row.t = {0, 0, 600};
  s.summary.results.push_back(h);
  s.vertices[1] = tile_surface();
  return s;
}

PickRow pick_at(const Eigen::Vector3d& point) {
  PickRow p;
  p.grasp.translation() = point;  // approach = the camera's +z: down onto the tile's top
  p.gripper = "suction:10,5,10,100";
  return p;
}

const OperatingPoint kRight{10, 15};
const Eigen::Vector3d kBin(200, 200, 100);

TEST(PickSuccess, AClearPickOnItsGraspSucceeds) {
  const Scene s = scene();
  const PickSummary r = evaluate_picks(s.dataset, s.summary, {pick_at({0, 0, 595})}, s.vertices, kBin, kRight);
  ASSERT_EQ(r.firsts.size(), 1u);
  EXPECT_TRUE(r.firsts[0].right);
  EXPECT_TRUE(r.firsts[0].on_grasp);
  EXPECT_EQ(r.firsts[0].collision, "");
  EXPECT_EQ(r.success, 1u);
  EXPECT_EQ(r.images, 1u);
  EXPECT_DOUBLE_EQ(r.rate(), 1.0);
}

TEST(PickSuccess, ATileLyingOverThePickedOneIsHit) {
  const Scene s = scene({{10, 0, 580}});  // 20 mm above, across the cup's axis
  const PickSummary r = evaluate_picks(s.dataset, s.summary, {pick_at({0, 0, 595})}, s.vertices, kBin, kRight);
  EXPECT_EQ(r.firsts[0].collision, "part 1 (obj_id 1)");
  EXPECT_EQ(r.success, 0u);
  // Beside it, out of the gripper's way: nothing is hit.
  const Scene beside = scene({{70, 0, 580}});
  EXPECT_EQ(evaluate_picks(beside.dataset, beside.summary, {pick_at({0, 0, 595})}, beside.vertices,
                           kBin, kRight).success, 1u);
}

TEST(PickSuccess, OffTheGraspOrOnAWrongDetectionFails) {
  Scene s = scene();
  // The detection says the tile is 8 mm to the side: its cup (10 mm) still lies on the true
  // tile's top and seals.
  s.summary.results[0].row.t = {8, 0, 600};
  PickSummary r = evaluate_picks(s.dataset, s.summary, {pick_at({8, 0, 595})}, s.vertices, kBin, kRight);
  EXPECT_TRUE(r.firsts[0].on_grasp);
  // 18 mm to the side the cup hangs over the tile's edge (at 20 mm): no seal.
  s.summary.results[0].row.t = {18, 0, 600};
  r = evaluate_picks(s.dataset, s.summary, {pick_at({18, 0, 595})}, s.vertices, kBin, kRight);
  EXPECT_FALSE(r.firsts[0].on_grasp);
  EXPECT_EQ(r.success, 0u);
  EXPECT_EQ(r.firsts[0].verdict(), "off the true grasp");
  // Above the tile by 2 mm the cup reaches it (within 5 % of the diameter, 2.9 mm); by 4 mm not.
  s.summary.results[0].row.t = {0, 0, 600};
  EXPECT_TRUE(evaluate_picks(s.dataset, s.summary, {pick_at({0, 0, 593})}, s.vertices, kBin, kRight).firsts[0].on_grasp);
  EXPECT_FALSE(evaluate_picks(s.dataset, s.summary, {pick_at({0, 0, 591})}, s.vertices, kBin, kRight).firsts[0].on_grasp);
  // Tilted 60 degrees from the face's normal the lip leaves the face.
  PickRow tilted = pick_at({0, 0, 595});
  tilted.grasp.linear() = Eigen::AngleAxisd(60 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_FALSE(evaluate_picks(s.dataset, s.summary, {tilted}, s.vertices, kBin, kRight).firsts[0].on_grasp);
  s.summary.results[0].translation_pct = 30;  // and eval found the pose wrong
  r = evaluate_picks(s.dataset, s.summary, {pick_at({8, 0, 595})}, s.vertices, kBin, kRight);
  EXPECT_FALSE(r.firsts[0].right);
  EXPECT_EQ(r.firsts[0].verdict(), "on a wrong detection");
}

// Parallel jaws (fingers 6 wide, 10 deep, 20 long: their tips 5 mm past the grasp point) about
// the tile's middle, closing along x.
PickRow jaws_at(double opening) {
  PickRow p = pick_at({0, 0, 600});
  p.width = opening;
  p.gripper = "parallel:6,10,20,10";
  return p;
}

TEST(PickSuccess, ParallelJawsHoldTheTileByTwoFacingSides) {
  const Scene s = scene();
  // Open 50 mm the jaws pass beside the 40 mm tile and close on its sides at x = +-20.
  PickSummary r = evaluate_picks(s.dataset, s.summary, {jaws_at(50)}, s.vertices, kBin, kRight);
  ASSERT_EQ(r.firsts.size(), 1u);
  EXPECT_TRUE(r.firsts[0].on_grasp);
  EXPECT_EQ(r.firsts[0].collision, "");
  EXPECT_EQ(r.success, 1u);
  // Turned a quarter about the approach they close on the sides at y = +-20.
  PickRow turned = jaws_at(50);
  turned.grasp.linear() = Eigen::AngleAxisd(90 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_EQ(evaluate_picks(s.dataset, s.summary, {turned}, s.vertices, kBin, kRight).success, 1u);
  // Open 30 mm the fingers come down on the tile itself; between them only its top and bottom,
  // which do not face them.
  r = evaluate_picks(s.dataset, s.summary, {jaws_at(30)}, s.vertices, kBin, kRight);
  EXPECT_FALSE(r.firsts[0].on_grasp);
  EXPECT_EQ(r.firsts[0].collision, "its own part");
  // 30 mm to the side, open 50: one jaw meets the tile's side, the other nothing.
  EXPECT_FALSE(evaluate_picks(s.dataset, s.summary, {[] { PickRow p = jaws_at(50); p.grasp.translation().x() = 30; return p; }()},
                              s.vertices, kBin, kRight).firsts[0].on_grasp);
  // A second tile lying beside it, 8 mm away: the open finger lands on it.
  const Scene crowded = scene({{48, 0, 600}});
  r = evaluate_picks(crowded.dataset, crowded.summary, {jaws_at(50)}, crowded.vertices, kBin, kRight);
  EXPECT_EQ(r.firsts[0].collision, "part 1 (obj_id 1)");
}

// Train and eval agree: every suction grasp train generates for a built-in part, planned at the
// part's true pose with the default tool, seals and touches nothing.
TEST(PickSuccess, EveryGeneratedGraspSealsAtItsOwnPose) {
  for (const char* name : {"builtin:bracket", "builtin:plate", "builtin:bolt", "builtin:tee"}) {
    const Mesh mesh = cli::load_part({name, {}}).mesh;
    const PpfModel model = train_ppf_model(mesh, PpfTrainParams{}, nullptr, test::test_device());
    ASSERT_FALSE(model.grasps.empty()) << name;
    Scene s;
    const double d = model.diameter;
    s.dataset.models[1].diameter = d;
    bop::GroundTruth gt;
    gt.model_to_camera.R = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    gt.model_to_camera.t = {10, -20, 700};
    s.dataset.images[{0, 0}].gt.push_back(gt);
    HypothesisResult h;
    h.gt_index = 0;
    h.row.R = gt.model_to_camera.R;
    h.row.t = gt.model_to_camera.t;
    s.summary.results.push_back(h);
    s.vertices[1] = sample_part_surface(mesh, d);
    const std::string tool = default_suction_gripper(d, model.grasps.front().size).describe();
    std::vector<PickRow> picks;
    for (const Grasp& g : model.grasps) {
      PickRow p;
      p.grasp = gt.model_to_camera.isometry() * g.frame();
      p.width = g.size;
      p.gripper = tool;
      picks.push_back(p);
    }
    const PickSummary r = evaluate_picks(s.dataset, s.summary, picks, s.vertices, std::nullopt, kRight);
    for (std::size_t k = 0; k < r.firsts.size(); ++k)
      EXPECT_TRUE(r.firsts[k].success()) << name << " grasp " << k << ": " << r.firsts[k].verdict();
  }
}

TEST(PickSuccess, TheBinsWallIsHitAndMissingRowsAreRefused) {
  const Scene s = scene();
  // The tile by the wall (x = 100): the cup over its edge at x = 97 reaches 102.
  Scene by_wall = s;
  by_wall.dataset.images[{0, 0}].camera.world_to_camera.t = {-97, 0, 605};
  const PickSummary r = evaluate_picks(by_wall.dataset, by_wall.summary, {pick_at({0, 0, 595})},
                                       by_wall.vertices, kBin, kRight);
  EXPECT_EQ(r.firsts[0].collision, "the bin's wall");
  EXPECT_EQ(evaluate_picks(by_wall.dataset, by_wall.summary, {pick_at({0, 0, 595})}, by_wall.vertices,
                           std::nullopt, kRight).success, 1u);  // no bin known: not checked
  PickRow missing = pick_at({0, 0, 595});
  missing.rank = 3;
  EXPECT_THROW(evaluate_picks(s.dataset, s.summary, {missing}, s.vertices, kBin, kRight), InputError);
}

TEST(PickSuccess, ReadsTheFirstPicksOfAPicksFile) {
  const auto file = std::filesystem::temp_directory_path() / "binpick_test_first_picks.csv";
  std::ofstream(file)
      << "scene_id,im_id,obj_id,rank,order,grasp,R,t,approach,width,clearance,score,gripper,reason\n"
      << "0,0,1,0,2,3,1 0 0 0 1 0 0 0 1,1 2 3,0 0 1,10.000,5.000,0.9,\"suction:10,5,10,100\",\n"
      << "0,0,1,1,1,4,1 0 0 0 1 0 0 0 1,4 5 6,0 0 1,10.000,5.000,0.8,\"suction:10,5,10,100\",\n"
      << "0,0,1,2,,,,,,,,0.5,\"suction:10,5,10,100\",\"score 0.50 below --pick-score 0.70\"\n";
  const auto rows = read_first_picks(file);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].rank, 1);
  EXPECT_TRUE(rows[0].grasp.translation().isApprox(Eigen::Vector3d(4, 5, 6)));
  EXPECT_EQ(rows[0].gripper, "suction:10,5,10,100");
  EXPECT_EQ(rows[0].width, 10.0);
  std::ofstream(file) << "scene_id,im_id,obj_id,rank,order,grasp,R,t,approach,width,clearance,score,gripper,reason\n"
                      << "0,0,1,1,1,4,1 0 0 0 1 0 0 0,4 5 6,0 0 1,10.000,5.000,0.8,\"suction:10,5,10,100\",\n";
  EXPECT_THROW(read_first_picks(file), InputError);
  std::ofstream(file) << "scene_id,im_id,score\n";
  EXPECT_THROW(read_first_picks(file), InputError);
  std::filesystem::remove(file);
}

}  // namespace
