// Grasps (host/core/grasp.hpp): the suction grasps train finds on a part's faces, the grasps and
// grippers JSON files, their place in the model file, and a grasp's frame by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "host/core/error.hpp"
#include "host/core/grasp.hpp"
#include "host/formats/grasps/grasp_json.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/ppf_model_file.hpp"
#include "host/train/suction_grasps.hpp"
#include "host/train/surface_sampling.hpp"
#include "tests/support/test_meshes.hpp"

using namespace binpick;

namespace {

std::string refusal(const std::string& text) {
  try {
    parse_grasps_json(text, "g.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Grasp, FrameAndTransformByHand) {
  Grasp g;
  g.kind = Grasp::Kind::parallel;
  g.point = {10, 0, 5};
  g.approach = {0, 0, -1};  // from above, down
  g.closing = {1, 0, 0};
  const Eigen::Isometry3d f = g.frame();
  EXPECT_TRUE(f.linear().isApprox(Eigen::Matrix3d(Eigen::Vector3d(1, -1, -1).asDiagonal())));
  EXPECT_NEAR(f.linear().determinant(), 1, 1e-12);
  // The part turned a quarter about z and moved: the grasp's frame moves with it.
  Eigen::Isometry3d part = Eigen::Isometry3d::Identity();
  part.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  part.translation() = Eigen::Vector3d(100, 200, 300);
  const Eigen::Isometry3d in_camera = part * f;
  EXPECT_TRUE(in_camera.translation().isApprox(Eigen::Vector3d(100, 210, 305)));
  EXPECT_TRUE(in_camera.linear().col(0).isApprox(Eigen::Vector3d(0, 1, 0)));   // closing turned
  EXPECT_TRUE(in_camera.linear().col(2).isApprox(Eigen::Vector3d(0, 0, -1)));  // still down
  for (const Eigen::Vector3d& a : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0),
                                  Eigen::Vector3d(0.6, 0.8, 0)})
    EXPECT_NEAR(across(a).dot(a), 0, 1e-12);
}

TEST(SuctionGrasps, OnEveryFaceOfABoxAndOnlyOnFlatFaces) {
  const Mesh mesh = test::box({60, 40, 20});
  const PointCloud surface = sample_surface(mesh, 40000);
  SuctionGraspOptions o;
  o.cup_diameter = 10;
  o.flatness = 0.5;
  o.spacing = 1.5;
  o.apart = 10;
  o.max_grasps = 200;  // all of them: every face's
  const std::vector<Grasp> grasps = find_suction_grasps(surface, o);
  ASSERT_FALSE(grasps.empty());
  int faces[6] = {};
  for (const Grasp& g : grasps) {
    EXPECT_EQ(g.kind, Grasp::Kind::suction);
    EXPECT_EQ(g.size, 10);
    // On a face, a cup's radius in from its edges, approaching along the face's inward normal.
    const Eigen::Vector3d p = g.point, a = g.approach;
    const int axis = int(std::distance(a.data(), std::max_element(a.data(), a.data() + 3, [](double x, double y) {
                                           return std::abs(x) < std::abs(y);
                                         })));
    EXPECT_NEAR(std::abs(a[axis]), 1, 1e-3);
    const Eigen::Vector3d size(60, 40, 20);
    EXPECT_NEAR(p[axis], a[axis] > 0 ? 0 : size[axis], 1e-3);  // approach into the part
    for (int k = 0; k < 3; ++k)
      if (k != axis) {
        EXPECT_GE(p[k], 5 - 1.5);
        EXPECT_LE(p[k], size[k] - 5 + 1.5);
      }
    ++faces[2 * axis + (a[axis] > 0)];
  }
  for (int f = 0; f < 6; ++f) EXPECT_GT(faces[f], 0) << "face " << f;
  // The nearest the centre first: the first grasp is a big face's middle.
  EXPECT_NEAR(grasps.front().point.x(), 30, 3);
  EXPECT_NEAR(grasps.front().point.y(), 20, 3);
  // A cup wider than the 20 mm sides finds only the two big faces; wider than all, none.
  o.cup_diameter = 30;
  for (const Grasp& g : find_suction_grasps(surface, o)) EXPECT_NEAR(std::abs(g.approach.z()), 1, 1e-3);
  o.cup_diameter = 45;
  EXPECT_TRUE(find_suction_grasps(surface, o).empty());
  EXPECT_TRUE(find_suction_grasps(PointCloud{}, o).empty());
}

TEST(SuctionGrasps, NoneOnATubeNarrowerThanTheCupAndNoneUnderAnOverhang) {
  // An L-bracket: no grasp's cup has anything of the part above its face within its radius (the
  // inner corner's faces meet the other leg beside the cup, not over it).
  const Mesh l = test::l_bracket();
  const PointCloud surface = sample_surface(l, 60000);
  SuctionGraspOptions o;
  o.cup_diameter = 8;
  o.flatness = 0.5;
  o.spacing = 1.2;
  const std::vector<Grasp> grasps = find_suction_grasps(surface, o);
  ASSERT_FALSE(grasps.empty());
  for (const Grasp& g : grasps)
    for (const Eigen::Vector3f& q : surface.points) {
      const Eigen::Vector3d d = q.cast<double>() - g.point;
      const double height = -d.dot(g.approach);  // above the face, outward
      const double radial = (d + height * g.approach).norm();
      EXPECT_FALSE(height > 0.6 && radial < 3.9) << g.point.transpose();
    }
  // A torus' tube (radius 6 mm) curves away under a 10 mm cup by 2.1 mm: no grasp.
  const PointCloud tube = sample_surface(test::torus(64, 32), 60000);
  o.cup_diameter = 10;
  EXPECT_TRUE(find_suction_grasps(tube, o).empty());
  o.cup_diameter = 4;  // 0.34 mm: the lip follows it
  o.flatness = 0.6;
  EXPECT_FALSE(find_suction_grasps(tube, o).empty());
}

TEST(GraspsJson, ReadsBothKindsAndRefusesBadGrasps) {
  const std::vector<Grasp> g = parse_grasps_json(
      R"({"suction": [{"point": [1, 2, 3], "approach": [0, 0, -2], "cup_diameter": 12}],
          "parallel": [{"centre": [0, 0, 10], "approach": [0, 0, -1], "closing": [1, 0, 0.1],
                        "width": 30}]})",
      "g.json");
  ASSERT_EQ(g.size(), 2u);
  EXPECT_EQ(g[0].kind, Grasp::Kind::suction);
  EXPECT_TRUE(g[0].approach.isApprox(Eigen::Vector3d(0, 0, -1)));
  EXPECT_NEAR(g[0].closing.dot(g[0].approach), 0, 1e-12);
  EXPECT_EQ(g[1].kind, Grasp::Kind::parallel);
  EXPECT_TRUE(g[1].closing.isApprox(Eigen::Vector3d(1, 0, 0)));  // made perpendicular
  EXPECT_EQ(g[1].size, 30);
  EXPECT_EQ(parse_grasps_json(grasps_json(g), "again").size(), 2u);
  EXPECT_EQ(parse_grasps_json(grasps_json(g), "again")[1].point, g[1].point);

  EXPECT_EQ(refusal("[1]"), "g.json: a JSON object of \"suction\" and \"parallel\" grasps expected");
  EXPECT_EQ(refusal("{}"), "g.json: no grasp");
  EXPECT_EQ(refusal(R"({"vacuum": []})"), "g.json: unknown key \"vacuum\" (\"suction\", \"parallel\")");
  EXPECT_EQ(refusal(R"({"suction": [{"point": [1, 2], "approach": [0, 0, 1], "cup_diameter": 5}]})"),
            "g.json: suction grasp 0: \"point\" (3 numbers) expected");
  EXPECT_EQ(refusal(R"({"suction": [{"point": [1, 2, 3], "approach": [0, 0, 0], "cup_diameter": 5}]})"),
            "g.json: suction grasp 0: \"approach\" is zero");
  EXPECT_EQ(refusal(R"({"suction": [{"point": [1, 2, 3], "approach": [0, 0, 1], "cup_diameter": -5}]})"),
            "g.json: suction grasp 0: \"cup_diameter\" must be positive");
  EXPECT_EQ(refusal(R"({"parallel": [{"centre": [1, 2, 3], "approach": [0, 0, 1], "closing": [0, 0.1, 1], "width": 5}]})"),
            "g.json: parallel grasp 0: \"closing\" must be across \"approach\"");
  EXPECT_NE(refusal("{").find("g.json: not JSON"), std::string::npos);
  EXPECT_THROW(read_grasps_json("/nonexistent/g.json"), InputError);
}

TEST(GripperSpec, FromTextOrFileAndRefusals) {
  const Gripper s = parse_gripper("suction:10,5,12,80");
  EXPECT_EQ(s.kind, Grasp::Kind::suction);
  EXPECT_EQ(s.describe(), "suction:10,5,12,80");
  const Gripper p = parse_gripper("parallel:6,10,40,8");
  EXPECT_EQ(p.kind, Grasp::Kind::parallel);
  EXPECT_DOUBLE_EQ(p.length(), 38);
  const auto file = std::filesystem::temp_directory_path() / "binpick_test_gripper.json";
  std::ofstream(file) << R"({"parallel": {"finger_width": 6, "finger_depth": 10, "finger_length": 40, "palm_height": 8}})";
  EXPECT_EQ(parse_gripper(file.string()).describe(), "parallel:6,10,40,8");
  std::ofstream(file) << R"({"suction": {"cup_diameter": 10}})";
  EXPECT_THROW(parse_gripper(file.string()), InputError);
  std::filesystem::remove(file);
  for (const char* bad : {"suction:10,5,12", "suction:10,5,12,x", "parallel:6,-10,40,8", "suction:",
                          "/nonexistent/gripper.json"})
    EXPECT_THROW(parse_gripper(bad), InputError) << bad;
}

TEST(PpfModelFile, GraspsRoundTripAndVersionSixIsStillRead) {
  Grasp g;
  g.kind = Grasp::Kind::parallel;
  g.point = {1, 2, 3};
  g.closing = {0, 1, 0};
  g.size = 7;
  const Mesh mesh = test::box({60, 40, 20});
  PpfModel trained = train_ppf_model(mesh, PpfTrainParams{});
  ASSERT_FALSE(trained.grasps.empty());  // the box's faces hold the default cup
  EXPECT_NEAR(trained.grasps.front().size, kDefaultCupRatio * trained.diameter, 1e-4);
  trained.grasps.push_back(g);
  const PpfModel back = parse_ppf_model(serialize_ppf_model(trained), "box.ppfm");
  ASSERT_EQ(back.grasps.size(), trained.grasps.size());
  EXPECT_EQ(back.grasps.back().kind, Grasp::Kind::parallel);
  EXPECT_EQ(back.grasps.back().point, g.point);
  EXPECT_EQ(back.grasps.back().size, 7);
  EXPECT_TRUE(parse_ppf_model(serialize_ppf_model(trained, 6), "old.ppfm").grasps.empty());
  // A grasp that is not one: corrupt.
  PpfModel bad = trained;
  bad.grasps.back().approach = {0, 0, 2};
  try {
    parse_ppf_model(serialize_ppf_model(bad), "bad.ppfm");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is corrupt (grasp "), std::string::npos) << e.what();
  }
}

}  // namespace
