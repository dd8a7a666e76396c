#include "fuzz/targets.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "host/core/error.hpp"
#include "host/detect/params/bin_pose_file.hpp"
#include "host/formats/grasps/grasp_json.hpp"
#include "host/detect/params/bin_spec.hpp"
#include "host/detect/params/params_file.hpp"
#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/models_info.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/formats/bop/test_targets.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/train/ppf_model_file.hpp"

namespace binpick::fuzz {
namespace {

namespace fs = std::filesystem;

// The (empty) directory of this process where glTF buffers and OBJ materials named by an input
// are looked up; every other reader takes the bytes themselves.
class Scratch {
 public:
  Scratch()
      : dir_(fs::temp_directory_path() / ("binpick_fuzz_" + std::to_string(::getpid()))) {
    fs::create_directories(dir_ / "empty");
  }
  ~Scratch() {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  const fs::path& dir() const { return dir_; }

 private:
  fs::path dir_;
};

fs::path empty_dir() {
  static const Scratch scratch;
  return scratch.dir() / "empty";
}

void parse_mesh(std::string_view bytes, std::string_view format) {
  parse_model(bytes, format, ModelOptions{}, empty_dir());
}

}  // namespace

void parse_ply(std::string_view bytes) { parse_mesh(bytes, "ply"); }
void parse_stl(std::string_view bytes) { parse_mesh(bytes, "stl"); }
void parse_obj(std::string_view bytes) { parse_mesh(bytes, "obj"); }
void parse_gltf(std::string_view bytes) { parse_mesh(bytes, "gltf"); }

void parse_ppfm(std::string_view bytes) { parse_ppf_model(bytes, "fuzz.ppfm"); }

void parse_camera(std::string_view bytes) { bop::parse_camera(bytes, "camera.json"); }
void parse_scene_camera(std::string_view bytes) {
  bop::parse_scene_cameras(bytes, "scene_camera.json");
}
void parse_scene_gt(std::string_view bytes) { bop::parse_scene_gt(bytes, "scene_gt.json"); }
void parse_scene_gt_info(std::string_view bytes) {
  bop::parse_scene_gt_info(bytes, "scene_gt_info.json");
}
void parse_models_info(std::string_view bytes) {
  bop::parse_models_info(std::string(bytes), "models_info.json");
}

// Depth images are read as 16-bit, intensity images and masks as 8-bit: both readers see every
// input, and it parses if either accepts it.
void parse_png(std::string_view bytes) {
  bool parsed = false;
  try {
    decode_png16(bytes, "image.png");
    parsed = true;
  } catch (const InputError&) {
  }
  try {
    decode_png8(bytes, "image.png");
  } catch (const InputError&) {
    if (!parsed) throw;
  }
}

void parse_results_csv(std::string_view bytes) {
  bop::parse_results_csv(std::string(bytes), "results.csv");
}

// The file as `detect --params` reads it, with the --roi and --bin texts it may hold.
void parse_params(std::string_view bytes) {
  DetectParams params;
  apply_params_text(bytes, "params.json", params);
  parse_roi(params.roi);
  parse_bin(params.bin);
}

void parse_bin_pose(std::string_view bytes) { binpick::parse_bin_pose(bytes, "bin_pose.json"); }

void parse_grasps(std::string_view bytes) { parse_grasps_json(bytes, "grasps.json"); }
void parse_gripper(std::string_view bytes) { parse_gripper_json(bytes, "gripper.json"); }

void parse_test_targets(std::string_view bytes) {
  bop::parse_test_targets(std::string(bytes), "test_targets_bop19.json");
}

const std::vector<Target>& all_targets() {
  static const std::vector<Target> targets = {
      {"ply", parse_ply},
      {"stl", parse_stl},
      {"obj", parse_obj},
      {"gltf", parse_gltf},
      {"ppfm", parse_ppfm},
      {"camera", parse_camera},
      {"scene_camera", parse_scene_camera},
      {"scene_gt", parse_scene_gt},
      {"scene_gt_info", parse_scene_gt_info},
      {"models_info", parse_models_info},
      {"png", parse_png},
      {"results_csv", parse_results_csv},
      {"params", parse_params},
      {"bin_pose", parse_bin_pose},
      {"grasps", parse_grasps},
      {"gripper", parse_gripper},
      {"test_targets", parse_test_targets},
  };
  return targets;
}

int run_one_input(Parse parse, const std::uint8_t* data, std::size_t size) {
  // The mesh loader warns about repairs it makes; millions of inputs would flood the output.
  static const bool quiet = [] {
    spdlog::set_level(spdlog::level::off);
    return true;
  }();
  (void)quiet;
  try {
    parse(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace binpick::fuzz
