// A BOP dataset as evaluation needs it: per image its ground truth and camera, per object its
// diameter and symmetries, and a label for the curves (the noise level it was made with).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/models_info.hpp"
#include "host/formats/bop/scene_files.hpp"

namespace binpick::eval {

struct ImageKey {
  int scene_id = 0, im_id = 0;
  auto operator<=>(const ImageKey&) const = default;
};

struct EvalImage {
  std::vector<bop::GroundTruth> gt;
  bop::SceneCamera camera;
  bop::SceneFiles files;  // SPLIT/NNNNNN and the sensor suffix
  // visib_fract of each gt instance from scene_gt_info.json; empty if the scene has none.
  std::vector<double> visib_fract;
};

struct Dataset {
  std::filesystem::path root;
  std::string label;   // "sigma 1 % of d" from synth.json's noise, else the directory name
  double noise = -1;   // synth.json's noise (fraction of the diameter); -1 if unknown
  bop::ModelsInfo models;
  std::map<ImageKey, EvalImage> images;
};

// Which images of a BOP dataset: the split directory and BOP's per-sensor suffix
// (scene_gt_SENSOR.json, depth_SENSOR/, ...; empty: none).
struct DatasetLayout {
  std::string split = "test";
  std::string sensor;
};

// Reads models/models_info.json and every SPLIT/NNNNNN/scene_gt.json and scene_camera.json of
// root (with the sensor's suffix), scene_gt_info.json where present (its visib_fract), and
// synth.json if present. Throws InputError naming the file
// for a missing or malformed file, and if root has no scene or an image of scene_gt.json has no
// camera.
Dataset load_dataset(const std::filesystem::path& root, const DatasetLayout& layout = {});

// "sigma 1 % of d" for noise 0.01 (two significant digits at most).
std::string noise_label(double noise);

}  // namespace binpick::eval
