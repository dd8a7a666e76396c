// The JSON files of a BOP dataset (bop.felk.cvut.cz; docs/formats.md): camera.json,
// scene_camera.json, scene_gt.json, scene_gt_info.json. Millimetres; rotations row-major.
// Readers validate what they read and name the file and the entry in their InputErrors. Each
// read_X(path) is parse_X(the file's bytes, path): parse_X takes the text in memory, and name
// is what its errors start with.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace binpick::bop {

struct Camera {  // camera.json
  double fx = 0, fy = 0, cx = 0, cy = 0;
  std::uint32_t width = 0, height = 0;
  double depth_scale = 1.0;
};

struct Pose {  // a rigid transform in mm
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Isometry3d isometry() const;
  static Pose from(const Eigen::Isometry3d& T);
};

struct SceneCamera {  // one image of scene_camera.json
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  double depth_scale = 1.0;
  Pose world_to_camera;  // cam_R_w2c, cam_t_w2c
};

struct GroundTruth {  // one object instance of scene_gt.json
  int obj_id = 1;
  Pose model_to_camera;  // cam_R_m2c, cam_t_m2c
};

struct GroundTruthInfo {  // one object instance of scene_gt_info.json
  std::array<int, 4> bbox_obj{-1, -1, -1, -1}, bbox_visib{-1, -1, -1, -1};  // x, y, w, h
  std::uint32_t px_count_all = 0, px_count_valid = 0, px_count_visib = 0;
  double visib_fract = 0;
};

// Keyed by image id.
using SceneCameras = std::map<int, SceneCamera>;
using SceneGroundTruth = std::map<int, std::vector<GroundTruth>>;
using SceneGroundTruthInfo = std::map<int, std::vector<GroundTruthInfo>>;

void write_camera(const std::filesystem::path& path, const Camera& camera);
Camera read_camera(const std::filesystem::path& path);
Camera parse_camera(std::string_view text, const std::string& name);

void write_scene_cameras(const std::filesystem::path& path, const SceneCameras& cameras);
SceneCameras read_scene_cameras(const std::filesystem::path& path);
SceneCameras parse_scene_cameras(std::string_view text, const std::string& name);

void write_scene_gt(const std::filesystem::path& path, const SceneGroundTruth& gt);
SceneGroundTruth read_scene_gt(const std::filesystem::path& path);
SceneGroundTruth parse_scene_gt(std::string_view text, const std::string& name);

void write_scene_gt_info(const std::filesystem::path& path, const SceneGroundTruthInfo& info);
SceneGroundTruthInfo read_scene_gt_info(const std::filesystem::path& path);
SceneGroundTruthInfo parse_scene_gt_info(std::string_view text, const std::string& name);

}  // namespace binpick::bop
