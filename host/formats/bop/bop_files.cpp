#include "host/formats/bop/bop_files.hpp"

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/core/atomic_file.hpp"
#include "host/core/read_file.hpp"

namespace binpick::bop {
namespace {

using nlohmann::json;

constexpr double kMaxU32 = 4294967295.0, kMinInt = -2147483648.0, kMaxInt = 2147483647.0;

void write_json(const std::filesystem::path& path, const json& j) {
  write_file_atomically(path, [&](std::ostream& out) { out << j.dump(1) << "\n"; });
}

json parse_json(std::string_view text, const std::string& name) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(name + " is not valid JSON: " + e.what());
  }
}

// Reading goes through Reader so that every error names the file and the entry.
struct Reader {
  const std::string& name;
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(name + ": " + where + ": " + what);
  }
  const json& member(const json& j, const char* key, const std::string& where) const {
    if (!j.is_object() || !j.contains(key)) fail(where, std::string("missing \"") + key + "\"");
    return j.at(key);
  }
  double number(const json& j, const char* key, const std::string& where) const {
    const json& v = member(j, key, where);
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      fail(where, std::string("\"") + key + "\" is not a finite number");
    return v.get<double>();
  }
  // A whole number in [lo, hi]: converting a double outside the target type is undefined.
  long long integer(const json& j, const char* key, const std::string& where, double lo,
                    double hi) const {
    const double v = number(j, key, where);
    if (v != std::floor(v) || v < lo || v > hi)
      fail(where, std::string("\"") + key + "\" must be an integer in [" +
                      std::to_string(static_cast<long long>(lo)) + ", " +
                      std::to_string(static_cast<long long>(hi)) + "], not " + std::to_string(v));
    return static_cast<long long>(v);
  }
  template <int N>
  Eigen::Matrix<double, N, 1> vector(const json& j, const char* key, const std::string& where) const {
    const json& v = member(j, key, where);
    if (!v.is_array() || v.size() != N)
      fail(where, std::string("\"") + key + "\" must be an array of " + std::to_string(N) + " numbers");
    Eigen::Matrix<double, N, 1> out;
    for (int i = 0; i < N; ++i) {
      if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
        fail(where, std::string("\"") + key + "\" holds a value that is not a finite number");
      out[i] = v[i].get<double>();
    }
    return out;
  }
  Eigen::Matrix3d matrix(const json& j, const char* key, const std::string& where) const {
    const auto v = vector<9>(j, key, where);
    return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(v.data());
  }
  Pose pose(const json& j, const char* r, const char* t, const std::string& where) const {
    Pose p{matrix(j, r, where), vector<3>(j, t, where)};
    const double err = (p.R.transpose() * p.R - Eigen::Matrix3d::Identity()).norm();
    if (err > 1e-3 || p.R.determinant() < 0) fail(where, std::string("\"") + r + "\" is not a rotation");
    return p;
  }
  // The image ids of a scene file: keys must be non-negative integers.
  template <class F>
  void for_each_image(const json& root, F&& f) const {
    if (!root.is_object()) fail("top level", "expected an object keyed by image id");
    for (auto it = root.begin(); it != root.end(); ++it) {
      int id = -1;
      try {
        std::size_t used = 0;
        id = std::stoi(it.key(), &used);
        if (used != it.key().size()) id = -1;
      } catch (const std::exception&) {
      }
      if (id < 0) fail("key \"" + it.key() + "\"", "image ids must be non-negative integers");
      f(id, it.value(), "image " + it.key());
    }
  }
};

json row_major(const Eigen::Matrix3d& R) {
  json a = json::array();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a.push_back(R(r, c));
  return a;
}
json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

}  // namespace

Eigen::Isometry3d Pose::isometry() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = t;
  return T;
}

Pose Pose::from(const Eigen::Isometry3d& T) { return {T.linear(), T.translation()}; }

void write_camera(const std::filesystem::path& path, const Camera& c) {
  write_json(path, {{"cx", c.cx}, {"cy", c.cy}, {"fx", c.fx}, {"fy", c.fy}, {"width", c.width},
                    {"height", c.height}, {"depth_scale", c.depth_scale}});
}

Camera read_camera(const std::filesystem::path& path) {
  return parse_camera(read_file_bytes(path), path.string());
}

Camera parse_camera(std::string_view text, const std::string& name) {
  const json j = parse_json(text, name);
  Reader r{name};
  Camera c{r.number(j, "fx", "camera"), r.number(j, "fy", "camera"), r.number(j, "cx", "camera"),
           r.number(j, "cy", "camera"),
           std::uint32_t(r.integer(j, "width", "camera", 0, kMaxU32)),
           std::uint32_t(r.integer(j, "height", "camera", 0, kMaxU32)),
           j.contains("depth_scale") ? r.number(j, "depth_scale", "camera") : 1.0};
  if (!(c.fx > 0 && c.fy > 0 && c.width > 0 && c.height > 0 && c.depth_scale > 0))
    r.fail("camera", "fx, fy, width, height and depth_scale must be positive");
  return c;
}

void write_scene_cameras(const std::filesystem::path& path, const SceneCameras& cameras) {
  json root = json::object();
  for (const auto& [id, c] : cameras)
    root[std::to_string(id)] = {{"cam_K", row_major(c.K)}, {"depth_scale", c.depth_scale},
                                {"cam_R_w2c", row_major(c.world_to_camera.R)},
                                {"cam_t_w2c", vec(c.world_to_camera.t)}};
  write_json(path, root);
}

SceneCameras read_scene_cameras(const std::filesystem::path& path) {
  return parse_scene_cameras(read_file_bytes(path), path.string());
}

SceneCameras parse_scene_cameras(std::string_view text, const std::string& name) {
  const json root = parse_json(text, name);
  Reader r{name};
  SceneCameras out;
  r.for_each_image(root, [&](int id, const json& j, const std::string& where) {
    SceneCamera c;
    c.K = r.matrix(j, "cam_K", where);
    if (!(c.K(0, 0) > 0 && c.K(1, 1) > 0)) r.fail(where, "cam_K has a non-positive focal length");
    c.depth_scale = j.contains("depth_scale") ? r.number(j, "depth_scale", where) : 1.0;
    if (!(c.depth_scale > 0)) r.fail(where, "depth_scale must be positive");
    if (j.contains("cam_R_w2c")) c.world_to_camera = r.pose(j, "cam_R_w2c", "cam_t_w2c", where);
    out[id] = c;
  });
  return out;
}

void write_scene_gt(const std::filesystem::path& path, const SceneGroundTruth& gt) {
  json root = json::object();
  for (const auto& [id, list] : gt) {
    json a = json::array();
    for (const auto& g : list)
      a.push_back({{"obj_id", g.obj_id}, {"cam_R_m2c", row_major(g.model_to_camera.R)},
                   {"cam_t_m2c", vec(g.model_to_camera.t)}});
    root[std::to_string(id)] = a;
  }
  write_json(path, root);
}

SceneGroundTruth read_scene_gt(const std::filesystem::path& path) {
  return parse_scene_gt(read_file_bytes(path), path.string());
}

SceneGroundTruth parse_scene_gt(std::string_view text, const std::string& name) {
  const json root = parse_json(text, name);
  Reader r{name};
  SceneGroundTruth out;
  r.for_each_image(root, [&](int id, const json& list, const std::string& where) {
    if (!list.is_array()) r.fail(where, "expected an array of object instances");
    auto& v = out[id];
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = where + ", instance " + std::to_string(i);
      v.push_back({int(r.integer(list[i], "obj_id", at, kMinInt, kMaxInt)),
                   r.pose(list[i], "cam_R_m2c", "cam_t_m2c", at)});
    }
  });
  return out;
}

void write_scene_gt_info(const std::filesystem::path& path, const SceneGroundTruthInfo& info) {
  json root = json::object();
  for (const auto& [id, list] : info) {
    json a = json::array();
    for (const auto& g : list)
      a.push_back({{"bbox_obj", g.bbox_obj}, {"bbox_visib", g.bbox_visib},
                   {"px_count_all", g.px_count_all}, {"px_count_valid", g.px_count_valid},
                   {"px_count_visib", g.px_count_visib}, {"visib_fract", g.visib_fract}});
    root[std::to_string(id)] = a;
  }
  write_json(path, root);
}

SceneGroundTruthInfo read_scene_gt_info(const std::filesystem::path& path) {
  return parse_scene_gt_info(read_file_bytes(path), path.string());
}

SceneGroundTruthInfo parse_scene_gt_info(std::string_view text, const std::string& name) {
  const json root = parse_json(text, name);
  Reader r{name};
  SceneGroundTruthInfo out;
  r.for_each_image(root, [&](int id, const json& list, const std::string& where) {
    if (!list.is_array()) r.fail(where, "expected an array of object instances");
    auto& v = out[id];
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = where + ", instance " + std::to_string(i);
      GroundTruthInfo g;
      const auto bo = r.vector<4>(list[i], "bbox_obj", at), bv = r.vector<4>(list[i], "bbox_visib", at);
      for (int k = 0; k < 4; ++k) {
        if (!(std::abs(bo[k]) <= kMaxInt && std::abs(bv[k]) <= kMaxInt))
          r.fail(at, "a bounding box value is out of range");
        g.bbox_obj[k] = int(bo[k]), g.bbox_visib[k] = int(bv[k]);
      }
      g.px_count_all = std::uint32_t(r.integer(list[i], "px_count_all", at, 0, kMaxU32));
      g.px_count_visib = std::uint32_t(r.integer(list[i], "px_count_visib", at, 0, kMaxU32));
      if (list[i].contains("px_count_valid"))
        g.px_count_valid = std::uint32_t(r.integer(list[i], "px_count_valid", at, 0, kMaxU32));
      g.visib_fract = r.number(list[i], "visib_fract", at);
      v.push_back(g);
    }
  });
  return out;
}

}  // namespace binpick::bop
