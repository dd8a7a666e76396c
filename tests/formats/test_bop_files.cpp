// BOP dataset files: PNG and JSON round trips, and bad files rejected with clear errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/core/error.hpp"
#include "host/core/read_file.hpp"

using namespace binpick;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("binpick_test_bop_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

}  // namespace

TEST(Png, SixteenAndEightBitRoundTrip) {
  const fs::path d = fresh_dir("png");
  std::mt19937 rng(1);
  GrayImage<std::uint16_t> depth{31, 7, std::vector<std::uint16_t>(31 * 7)};
  for (auto& v : depth.pixels) v = std::uint16_t(rng());
  write_png(d / "depth.png", depth);
  EXPECT_EQ(read_png16(d / "depth.png").pixels, depth.pixels);
  GrayImage<std::uint8_t> gray{5, 9, std::vector<std::uint8_t>(45)};
  for (auto& v : gray.pixels) v = std::uint8_t(rng());
  write_png(d / "gray.png", gray);
  EXPECT_EQ(read_png8(d / "gray.png").pixels, gray.pixels);
  // Bit depth is checked, not converted silently.
  EXPECT_NE(message_of([&] { read_png16(d / "gray.png"); }).find("16-bit"), std::string::npos);
}

TEST(Png, MissingTruncatedAndForeignFilesAreInputErrors) {
  const fs::path d = fresh_dir("png_bad");
  EXPECT_THROW(read_png16(d / "missing.png"), InputError);
  write_text(d / "text.png", "hello, not a png");
  EXPECT_NE(message_of([&] { read_png16(d / "text.png"); }).find("not a PNG"), std::string::npos);
  GrayImage<std::uint16_t> img{64, 64, std::vector<std::uint16_t>(64 * 64, 1234)};
  write_png(d / "full.png", img);
  std::ifstream in(d / "full.png", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  for (std::size_t cut : {std::size_t(9), std::size_t(40), bytes.size() / 2, bytes.size() - 5}) {
    std::ofstream(d / "cut.png", std::ios::binary).write(bytes.data(), std::streamsize(cut));
    EXPECT_THROW(read_png16(d / "cut.png"), InputError) << cut;
  }
}

TEST(Png, WritingAMismatchedImageLeavesNoFile) {
  const fs::path d = fresh_dir("png_partial");
  GrayImage<std::uint8_t> bad{10, 10, std::vector<std::uint8_t>(5)};
  EXPECT_THROW(write_png(d / "bad.png", bad), InputError);
  EXPECT_TRUE(fs::is_empty(d));
}

TEST(BopFiles, SceneFilesRoundTrip) {
  const fs::path d = fresh_dir("json");
  bop::Camera cam{1500.5, 1500.5, 799.5, 449.5, 1600, 900, 0.1};
  bop::write_camera(d / "camera.json", cam);
  const bop::Camera c2 = bop::read_camera(d / "camera.json");
  EXPECT_EQ(c2.fx, cam.fx);
  EXPECT_EQ(c2.width, cam.width);
  EXPECT_EQ(c2.depth_scale, cam.depth_scale);

  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(10.25, -3.5, 812.125);
  bop::SceneGroundTruth gt{{0, {{1, bop::Pose::from(T)}, {1, bop::Pose{}}}}};
  bop::write_scene_gt(d / "scene_gt.json", gt);
  const auto gt2 = bop::read_scene_gt(d / "scene_gt.json");
  ASSERT_EQ(gt2.at(0).size(), 2u);
  EXPECT_TRUE(gt2.at(0)[0].model_to_camera.R.isApprox(T.linear(), 1e-15));
  EXPECT_TRUE(gt2.at(0)[0].model_to_camera.t.isApprox(T.translation(), 1e-15));

  bop::SceneCameras sc{{0, {Eigen::Matrix3d::Identity() * 2, 0.1, bop::Pose::from(T)}}};
  bop::write_scene_cameras(d / "scene_camera.json", sc);
  EXPECT_TRUE(bop::read_scene_cameras(d / "scene_camera.json").at(0).world_to_camera.R.isApprox(T.linear()));

  bop::GroundTruthInfo info;
  info.bbox_obj = {1, 2, 3, 4};
  info.px_count_all = 100;
  info.px_count_visib = 40;
  info.visib_fract = 0.4;
  bop::write_scene_gt_info(d / "scene_gt_info.json", {{0, {info}}});
  const auto info2 = bop::read_scene_gt_info(d / "scene_gt_info.json");
  EXPECT_EQ(info2.at(0)[0].bbox_obj, info.bbox_obj);
  EXPECT_EQ(info2.at(0)[0].px_count_visib, 40u);
}

TEST(BopFiles, MalformedFilesNameTheFileAndTheEntry) {
  const fs::path d = fresh_dir("json_bad");
  write_text(d / "a.json", "{\"0\": [{\"obj_id\": 1, \"cam_R_m2c\": [1,0,0,0,1,0,0,0,1]}]}");
  const std::string m = message_of([&] { bop::read_scene_gt(d / "a.json"); });
  EXPECT_NE(m.find("a.json"), std::string::npos) << m;
  EXPECT_NE(m.find("cam_t_m2c"), std::string::npos) << m;
  write_text(d / "b.json", "{\"0\": [{\"obj_id\": 1, \"cam_R_m2c\": [2,0,0,0,1,0,0,0,1], \"cam_t_m2c\": [0,0,0]}]}");
  EXPECT_NE(message_of([&] { bop::read_scene_gt(d / "b.json"); }).find("not a rotation"), std::string::npos);
  write_text(d / "c.json", "{\"0\": [");
  EXPECT_NE(message_of([&] { bop::read_scene_gt(d / "c.json"); }).find("not valid JSON"), std::string::npos);
  write_text(d / "d.json", "{\"x\": []}");
  EXPECT_NE(message_of([&] { bop::read_scene_gt(d / "d.json"); }).find("image ids"), std::string::npos);
  write_text(d / "e.json", "{\"fx\": 0, \"fy\": 1, \"cx\": 1, \"cy\": 1, \"width\": 2, \"height\": 2}");
  EXPECT_NE(message_of([&] { bop::read_camera(d / "e.json"); }).find("positive"), std::string::npos);
  write_text(d / "f.json", "{\"0\": [{\"obj_id\": 1, \"cam_R_m2c\": [1,0,0,0,1,0,0,0,1], \"cam_t_m2c\": [0,null,0]}]}");
  EXPECT_THROW(bop::read_scene_gt(d / "f.json"), InputError);
  EXPECT_THROW(bop::read_camera(d / "missing.json"), InputError);
}

// The readers of bytes in memory (what the fuzzers call) give what the file readers give, and
// their errors start with the name they are handed.
TEST(BopFiles, TextInMemoryReadsAsTheFileDoes) {
  const fs::path d = fresh_dir("memory");
  bop::write_camera(d / "camera.json", bop::Camera{1500.5, 1501.5, 799.5, 449.5, 1600, 900, 0.1});
  const std::string text = read_file_bytes(d / "camera.json");
  const bop::Camera a = bop::read_camera(d / "camera.json"), b = bop::parse_camera(text, "cam");
  EXPECT_EQ(a.fy, b.fy);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(message_of([] { bop::parse_scene_gt("{\"0\": [", "in memory"); }).rfind("in memory", 0),
            0u);
  EXPECT_EQ(message_of([] { bop::parse_scene_cameras("[]", "sc"); }).rfind("sc: ", 0), 0u);
  EXPECT_EQ(message_of([] { bop::parse_scene_gt_info("{\"0\": 1}", "info"); }).rfind("info: ", 0),
            0u);

  GrayImage<std::uint16_t> depth{3, 2, {0, 1, 2, 65535, 4, 5}};
  write_png(d / "depth.png", depth);
  const auto decoded = decode_png16(read_file_bytes(d / "depth.png"), "depth");
  EXPECT_EQ(decoded.pixels, depth.pixels);
  EXPECT_EQ(message_of([] { decode_png8("not a png", "mask"); }), "mask is not a PNG file");
}
