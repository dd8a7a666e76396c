// opencv_ppf3d (bench/opencv), built only when OpenCV's surface_matching is found: on a generated
// ellipsoid and a crop that is its visible side, moved into the camera frame and voxel-subsampled, it
// finds the pose; an empty crop gives an entry with no poses; bad input exits 2 with a message
// and writes nothing. ctest runs it as smoke_opencv_ppf3d.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "host/formats/mesh/point_cloud_ply.hpp"
#include "tests/support/cli_run.hpp"

namespace fs = std::filesystem;
using binpick::PointCloud;
using binpick::test::CliRun;
using binpick::test::slurp;
using nlohmann::json;

namespace {

CliRun run_exe(const std::string& args, const fs::path& scratch) {
  const fs::path out = scratch / "stdout", err = scratch / "stderr";
  const std::string command = std::string("'") + OPENCV_PPF3D_EXE + "' " + args + " >'" +
                              out.string() + "' 2>'" + err.string() + "' </dev/null";
  const int raw = std::system(command.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
}

// The surface of an ellipsoid with semi-axes 30, 20 and 12 mm centred on the origin, n points
// (a Fibonacci lattice), outward normals. Curved on purpose: a box, with only three normal
// directions, crowds OpenCV's hash keys and its training takes minutes.
PointCloud ellipsoid_surface(int n) {
  const Eigen::Vector3f axes(30, 20, 12);
  PointCloud c;
  for (int i = 0; i < n; ++i) {
    const double phi = std::acos(1 - 2 * (i + 0.5) / n);
    const double theta = M_PI * (1 + std::sqrt(5.0)) * (i + 0.5);
    const Eigen::Vector3f u(static_cast<float>(std::cos(theta) * std::sin(phi)),
                            static_cast<float>(std::sin(theta) * std::sin(phi)),
                            static_cast<float>(std::cos(phi)));
    c.points.push_back(u.cwiseProduct(axes));
    c.normals.push_back(u.cwiseQuotient(axes).normalized());
  }
  return c;
}

// The points facing a camera at the origin, after the pose (R, t): the part of it a depth
// camera sees (a convex shape has no other self-occlusion), then averaged per voxel of `voxel` mm.
PointCloud visible_crop(const PointCloud& model, const Eigen::Matrix3f& R,
                        const Eigen::Vector3f& t, float voxel) {
  std::map<std::tuple<int, int, int>, std::pair<Eigen::Vector3f, Eigen::Vector3f>> cells;
  std::map<std::tuple<int, int, int>, int> counts;
  for (std::size_t i = 0; i < model.points.size(); ++i) {
    const Eigen::Vector3f p = R * model.points[i] + t;
    const Eigen::Vector3f n = R * model.normals[i];
    if (n.dot(-p) <= 0) continue;
    const auto key = std::make_tuple(static_cast<int>(std::floor(p.x() / voxel)),
                                     static_cast<int>(std::floor(p.y() / voxel)),
                                     static_cast<int>(std::floor(p.z() / voxel)));
    auto& cell = cells[key];
    if (counts[key]++ == 0) cell = {Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero()};
    cell.first += p;
    cell.second += n;
  }
  PointCloud crop;
  for (const auto& [key, cell] : cells) {
    crop.points.push_back(cell.first / static_cast<float>(counts[key]));
    crop.normals.push_back(cell.second.normalized());
  }
  return crop;
}

// The rotation error in degrees up to the ellipsoid's symmetries (the identity and the half turns
// about its three axes).
double symmetric_rotation_error_deg(const Eigen::Matrix3f& estimate, const Eigen::Matrix3f& truth) {
  double best = 180;
  for (const Eigen::Vector3f& s : {Eigen::Vector3f(1, 1, 1), Eigen::Vector3f(1, -1, -1),
                                  Eigen::Vector3f(-1, 1, -1), Eigen::Vector3f(-1, -1, 1)}) {
    const Eigen::Matrix3f d = estimate.transpose() * truth * s.asDiagonal();
    const double c = std::clamp((static_cast<double>(d.trace()) - 1) / 2, -1.0, 1.0);
    best = std::min(best, std::acos(c) * 180 / M_PI);
  }
  return best;
}

class OpenCvPpf3d : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = binpick::test::fresh_temp_dir("opencv_ppf3d");
    model_ = ellipsoid_surface(4000);
    binpick::write_point_cloud_ply(dir_ / "model.ply", model_);
    fs::create_directories(dir_ / "crops");
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string base_args() const {
    return "--model " + (dir_ / "model.ply").string() + " --crops " + (dir_ / "crops").string() +
           " --out " + (dir_ / "result.json").string();
  }
  fs::path dir_;
  PointCloud model_;
};

}  // namespace

TEST_F(OpenCvPpf3d, HelpDocumentsEveryOption) {
  const CliRun r = run_exe("--help", dir_);
  EXPECT_EQ(r.status, 0);
  for (const char* opt : {"--model", "--crops", "--out", "--sampling", "--distance-step", "--angles",
                          "--ref-ratio", "--scene-voxel-mm", "--position-threshold-mm",
                          "--rotation-threshold-deg", "--repeats", "--top"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt << "\n" << r.out;
}

TEST_F(OpenCvPpf3d, FindsThePoseAndSkipsAnEmptyCrop) {
  const Eigen::Matrix3f R =
      Eigen::AngleAxisf(0.9f, Eigen::Vector3f(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3f t(15, -10, 600);
  const float voxel = 3.0f;  // 4 % of the ellipsoid's 76 mm bounding box diagonal
  binpick::write_point_cloud_ply(dir_ / "crops" / "crop_0000.ply", visible_crop(model_, R, t, voxel));
  binpick::write_point_cloud_ply(dir_ / "crops" / "crop_0001.ply", PointCloud{});

  // --sampling 0.1 (9 cells per axis, about 300 model points): OpenCV's training is quadratic
  // in the pairs sharing a hash key and takes minutes at 0.05.
  const CliRun r = run_exe(base_args() + " --sampling 0.1 --scene-voxel-mm 3 "
                                         "--position-threshold-mm 10 --ref-ratio 0.2 --repeats 3",
                           dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  const json j = json::parse(slurp(dir_ / "result.json"));
  EXPECT_EQ(j.at("opencv_version").get<std::string>().substr(0, 2), "4.");
  EXPECT_GT(j.at("model_points").get<int>(), 100);
  EXPECT_EQ(j.at("params").at("opencv_model_grid_cells").get<int>(), 9);
  EXPECT_GE(j.at("train_ms").get<double>(), 0.0);
  EXPECT_EQ(j.at("params").at("reference_point_every").get<int>(), 5);
  EXPECT_NEAR(j.at("params").at("rotationThreshold_rad").get<double>(), 20 * M_PI / 180, 1e-9);
  ASSERT_EQ(j.at("crops").size(), 2u);

  const json& c0 = j.at("crops")[0];
  EXPECT_EQ(c0.at("file"), "crop_0000.ply");
  EXPECT_GT(c0.at("points").get<int>(), 100);
  // The grid is sized so that OpenCV keeps nearly every point of the crop.
  EXPECT_GT(c0.at("opencv_points").get<double>(), 0.8 * c0.at("points").get<double>());
  EXPECT_GT(c0.at("ms").get<double>(), 0.0);
  ASSERT_FALSE(c0.at("poses").empty()) << c0.dump();
  EXPECT_LE(c0.at("poses").size(), 5u);
  // OpenCV's clustering merges poses by rotation magnitude only and averages their quaternions
  // without aligning signs, so its most voted pose can be off in rotation: ask for one pose among
  // the top 5 within 15 degrees (up to symmetry) and 5 mm, and the most voted within 5 mm.
  double best_rotation = 180, best_translation = 1e9;
  for (std::size_t k = 0; k < c0.at("poses").size(); ++k) {
    const json& pose = c0.at("poses")[k];
    Eigen::Matrix3f Re;
    Eigen::Vector3f te;
    for (int i = 0; i < 9; ++i) Re(i / 3, i % 3) = pose.at("R")[i].get<float>();
    for (int i = 0; i < 3; ++i) te[i] = pose.at("t")[i].get<float>();
    EXPECT_LT((Re * Re.transpose() - Eigen::Matrix3f::Identity()).norm(), 1e-3) << Re;
    EXPECT_NEAR(Re.determinant(), 1.0f, 1e-3f);
    EXPECT_GT(pose.at("votes").get<double>(), 0);
    if (k == 0) {
      EXPECT_LT((te - t).norm(), 5.0f) << pose.dump();
    }
    const double rotation = symmetric_rotation_error_deg(Re, R);
    if (rotation < 15 && (te - t).norm() < best_translation) {
      best_rotation = rotation;
      best_translation = (te - t).norm();
    }
  }
  EXPECT_LT(best_rotation, 15.0) << c0.dump();
  EXPECT_LT(best_translation, 5.0) << c0.dump();

  const json& c1 = j.at("crops")[1];
  EXPECT_EQ(c1.at("file"), "crop_0001.ply");
  EXPECT_EQ(c1.at("points"), 0);
  EXPECT_TRUE(c1.at("poses").empty());
}

TEST_F(OpenCvPpf3d, BadInputExitsTwoWithAMessageAndNoFile) {
  const fs::path out = dir_ / "result.json";
  // No crop at all yet.
  CliRun r = run_exe(base_args(), dir_);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("crop_"), std::string::npos) << r.err;

  binpick::write_point_cloud_ply(dir_ / "crops" / "crop_0000.ply", ellipsoid_surface(300));
  for (const std::string bad :
       {"--sampling nan", "--sampling 0", "--sampling 2", "--ref-ratio 0", "--ref-ratio -1",
        "--angles 0", "--repeats 0", "--top 0", "--scene-voxel-mm -3", "--scene-voxel-mm inf",
        "--position-threshold-mm 0", "--rotation-threshold-deg 720", "--angles x"}) {
    r = run_exe(base_args() + " " + bad, dir_);
    EXPECT_EQ(r.status, 2) << bad << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << bad;
  }
  r = run_exe("--model " + (dir_ / "missing.ply").string() + " --crops " + (dir_ / "crops").string() +
                  " --out " + out.string(), dir_);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("missing.ply"), std::string::npos) << r.err;
  r = run_exe(base_args().replace(base_args().find(out.string()), out.string().size(),
                                  (dir_ / "no_such_dir" / "r.json").string()), dir_);
  EXPECT_EQ(r.status, 2) << r.err;

  // A malformed crop, then a crop with a NaN coordinate.
  std::ofstream(dir_ / "crops" / "crop_0001.ply") << "ply\nformat ascii 1.0\nelement vertex 3\n"
                                                     "property float x\nend_header\n1 2\n";
  r = run_exe(base_args(), dir_);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("crop_0001.ply"), std::string::npos) << r.err;
  std::ofstream(dir_ / "crops" / "crop_0001.ply")
      << "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
         "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nend_header\n"
         "nan 0 0 0 0 1\n";
  r = run_exe(base_args(), dir_);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_FALSE(fs::exists(out));
}
