// The --bin-pose file (host/detect/params/bin_pose_file.cpp): what it accepts and refuses, and that
// a bin written is read back as it was; and a bin found in an image, written and given back,
// makes the same region (the mask of the pixels detection may use) as the fit did.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <Eigen/Geometry>

#include "host/core/error.hpp"
#include "host/detect/bin/bin_fit.hpp"
#include "host/detect/bin/bin_planes.hpp"
#include "host/detect/bin/scene_mask.hpp"
#include "host/detect/params/bin_pose_file.hpp"
#include "host/detect/scene/depth_to_points.hpp"
#include "tests/detect/bin/bin_fit_check.hpp"
#include "tests/detect/bin/bin_scene.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

const char* kPose = R"({"cam_R_bin": [1, 0, 0, 0, -0.906308, 0.422618, 0, -0.422618, -0.906308],
                        "cam_t_bin": [12.5, -40, 2150], "interior_mm": [600, 400, 300],
                        "calibrated": "2026-12-07"})";

}  // namespace

TEST(BinPoseFile, ReadsTheFrameAndTheInterior) {
  const BinSpec spec = parse_bin_pose(kPose, "pose.json");
  EXPECT_EQ(spec.mode, BinSpec::Mode::given);
  EXPECT_TRUE(spec.t.isApprox(Eigen::Vector3d(12.5, -40, 2150)));
  EXPECT_EQ(spec.size, Eigen::Vector3d(600, 400, 300));
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, -0.906308, 0.422618, 0, -0.422618, -0.906308;  // read row-major
  EXPECT_LT((spec.R - R).cwiseAbs().maxCoeff(), 1e-5);
  // Taken to the nearest rotation: six digits are not exactly orthonormal.
  EXPECT_NEAR((spec.R.transpose() * spec.R - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
}

TEST(BinPoseFile, TurnsTheFrameSoThatXRunsAlongTheLongerSide) {
  const BinSpec spec = parse_bin_pose(
      R"({"cam_R_bin": [1,0,0, 0,-1,0, 0,0,-1], "cam_t_bin": [0,0,1000], "interior_mm": [300,500,200]})",
      "pose.json");
  EXPECT_EQ(spec.size, Eigen::Vector3d(500, 300, 200));
  // The new x is the old y, seen in the camera as -y; z unchanged.
  EXPECT_TRUE(spec.R.col(0).isApprox(Eigen::Vector3d(0, -1, 0)));
  EXPECT_TRUE(spec.R.col(2).isApprox(Eigen::Vector3d(0, 0, -1)));
  EXPECT_NEAR(spec.R.determinant(), 1.0, 1e-12);
}

TEST(BinPoseFile, RefusesWhatIsNotABinPose) {
  for (const char* bad : {
           "", "[]", "{", R"({"cam_t_bin": [0,0,1], "interior_mm": [1,1,1]})",
           R"({"cam_R_bin": [1,0,0,0,1,0,0,0], "cam_t_bin": [0,0,1], "interior_mm": [1,1,1]})",
           R"({"cam_R_bin": [1,0,0,0,1,0,0,0,"1"], "cam_t_bin": [0,0,1], "interior_mm": [1,1,1]})",
           R"({"cam_R_bin": [2,0,0,0,1,0,0,0,1], "cam_t_bin": [0,0,1], "interior_mm": [1,1,1]})",
           R"({"cam_R_bin": [1,0,0,0,1,0,0,0,-1], "cam_t_bin": [0,0,1], "interior_mm": [1,1,1]})",
           R"({"cam_R_bin": [1,0,0,0,1,0,0,0,1], "cam_t_bin": [0,0], "interior_mm": [1,1,1]})",
           R"({"cam_R_bin": [1,0,0,0,1,0,0,0,1], "cam_t_bin": [0,0,1], "interior_mm": [1,0,1]})",
           R"({"cam_R_bin": [1,0,0,0,1,0,0,0,1], "cam_t_bin": [0,0,1e999], "interior_mm": [1,1,1]})",
       }) {
    try {
      parse_bin_pose(bad, "cell.json");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cell.json"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(read_bin_pose("/nonexistent/bin_pose.json"), InputError);
}

TEST(BinPoseFile, AFoundBinWrittenAndGivenBackMakesTheSameRegion) {
  BinSceneSpec s;
  s.tilt_deg = 20, s.yaw_deg = 25;
  const BinScene scene = make_bin_scene(s);
  const BinFit found = fit(scene, {BinSpec::Mode::sized, {400, 300, 180}});
  ASSERT_TRUE(found.found) << found.why;
  const std::filesystem::path file = fresh_temp_dir("bin_pose") / "bin_pose.json";
  write_bin_pose(file, found.axes, found.origin, found.interior);
  const BinSpec spec = read_bin_pose(file);
  const PointImage pts = depth_to_points_reference(scene.depth, scene.cam);
  BinFitOptions o;
  o.spec = spec;
  const BinFit given = fit_bin(ocl::Device::shared(), pts.xyzw, pts.width, pts.height, o);
  ASSERT_TRUE(given.found && given.given);
  EXPECT_LT((given.axes - found.axes).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((given.origin - found.origin).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(given.interior, found.interior);
  EXPECT_EQ(given.tol, found.tol);
  EXPECT_NE(describe(given).find("given"), std::string::npos) << describe(given);
  // The region's boxes and walls, hence the mask, are the fit's.
  const RegionBox a = bin_interior_box(found, 10, 50, found.tol), b = bin_interior_box(given, 10, 50, given.tol);
  EXPECT_EQ(a.R, b.R);
  EXPECT_EQ(a.lo, b.lo);
  EXPECT_EQ(a.hi, b.hi);
  EXPECT_LT((a.t - b.t).cwiseAbs().maxCoeff(), 1e-3);
  const BinWalls wa = bin_walls(found), wb = bin_walls(given);
  EXPECT_EQ(wa.reach, wb.reach);
  EXPECT_EQ(wa.height, wb.height);
  // All four walls: a fit seeing every side, a pose claiming every wall.
  EXPECT_EQ(wb.sides, 15u);
  EXPECT_EQ(wa.sides, 15u);
}
