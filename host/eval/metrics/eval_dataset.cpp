#include "host/eval/metrics/eval_dataset.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"

namespace binpick::eval {
namespace {

namespace fs = std::filesystem;

// A scene directory is named by its id in six digits (BOP); anything else is not a scene.
bool scene_id_of(const fs::path& dir, int& id) {
  const std::string name = dir.filename().string();
  if (name.empty() || name.size() > 9) return false;
  for (char c : name)
    if (c < '0' || c > '9') return false;
  id = std::stoi(name);
  return true;
}

void read_synth_manifest(Dataset& d) {
  const fs::path path = d.root / "synth.json";
  if (!fs::exists(path)) return;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_file_bytes(path));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path.string() + " is not valid JSON: " + e.what());
  }
  if (j.is_object() && j.contains("noise") && j["noise"].is_number()) {
    d.noise = j["noise"].get<double>();
    d.label = noise_label(d.noise);
  }
}

std::string directory_label(const fs::path& root) {
  const fs::path clean = root.lexically_normal();
  const std::string name = (clean.has_filename() ? clean : clean.parent_path()).filename().string();
  return name.empty() ? root.string() : name;
}

}  // namespace

std::string noise_label(double noise) {
  return fmt::format("sigma {:.2g} % of d", noise * 100.0);
}

Dataset load_dataset(const fs::path& root, const DatasetLayout& layout) {
  bop::check_sensor_name(layout.sensor);
  if (!fs::is_directory(root)) throw InputError("dataset " + root.string() + " is not a directory");
  Dataset d;
  d.root = root;
  d.label = directory_label(root);
  read_synth_manifest(d);
  d.models = bop::read_models_info(root / "models" / "models_info.json");

  const fs::path test = root / layout.split;
  if (layout.split.empty() || !fs::is_directory(test))
    throw InputError("dataset " + root.string() + " has no " + layout.split +
                     "/ directory of scenes");
  std::vector<std::pair<int, fs::path>> scenes;
  for (const auto& entry : fs::directory_iterator(test)) {
    int id = 0;
    if (entry.is_directory() && scene_id_of(entry.path(), id)) scenes.emplace_back(id, entry.path());
  }
  std::sort(scenes.begin(), scenes.end());
  for (const auto& [scene_id, dir] : scenes) {
    const bop::SceneFiles files{dir, layout.sensor};
    // A bin still being written by synth has no scene_gt.json yet: not part of the dataset.
    if (!fs::exists(files.scene_gt())) continue;
    const bop::SceneGroundTruth gt = bop::read_scene_gt(files.scene_gt());
    const bop::SceneCameras cameras = bop::read_scene_cameras(files.scene_camera());
    bop::SceneGroundTruthInfo info;
    if (fs::exists(files.scene_gt_info())) info = bop::read_scene_gt_info(files.scene_gt_info());
    for (const auto& [im_id, instances] : gt) {
      const auto cam = cameras.find(im_id);
      if (cam == cameras.end())
        throw InputError(fmt::format("{}: image {} has ground truth but no camera",
                                     files.scene_camera().string(), im_id));
      for (const auto& g : instances)
        if (!d.models.count(g.obj_id))
          throw InputError(fmt::format("{}: image {} has obj_id {}, which models_info.json lacks",
                                       files.scene_gt().string(), im_id, g.obj_id));
      EvalImage& image = d.images[{scene_id, im_id}];
      image = {instances, cam->second, files, {}};
      if (const auto i = info.find(im_id); i != info.end()) {
        if (i->second.size() != instances.size())
          throw InputError(fmt::format("{}: image {} has {} entries, scene_gt.json has {}",
                                       files.scene_gt_info().string(), im_id, i->second.size(),
                                       instances.size()));
        for (const auto& g : i->second) image.visib_fract.push_back(g.visib_fract);
      }
    }
  }
  if (d.images.empty())
    throw InputError("dataset " + root.string() + " has no scene with a " +
                     bop::SceneFiles{{}, layout.sensor}.scene_gt().filename().string() +
                     " under " + layout.split + "/");
  return d;
}

}  // namespace binpick::eval
