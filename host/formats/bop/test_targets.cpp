#include "host/formats/bop/test_targets.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/atomic_file.hpp"
#include "host/core/error.hpp"

namespace binpick::bop {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

int non_negative_int(const json& entry, const char* key, const std::string& name,
                     std::size_t index) {
  const auto it = entry.find(key);
  if (it == entry.end() || !it->is_number_integer() || it->get<long long>() < 0 ||
      it->get<long long>() > 1'000'000'000)
    throw InputError(fmt::format("{}: entry {} has no non-negative integer \"{}\"", name,
                                 index, key));
  return static_cast<int>(it->get<long long>());
}

}  // namespace

std::vector<TestTarget> parse_test_targets(const std::string& text, const std::string& name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(name + " is not valid JSON: " + e.what());
  }
  if (!j.is_array()) throw InputError(name + " is not a JSON array of targets");
  std::vector<TestTarget> targets;
  std::set<std::tuple<int, int, int>> seen;
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_object()) throw InputError(fmt::format("{}: entry {} is not an object", name, i));
    TestTarget t;
    t.scene_id = non_negative_int(j[i], "scene_id", name, i);
    t.im_id = non_negative_int(j[i], "im_id", name, i);
    t.obj_id = non_negative_int(j[i], "obj_id", name, i);
    t.inst_count = non_negative_int(j[i], "inst_count", name, i);
    if (!seen.insert({t.scene_id, t.im_id, t.obj_id}).second)
      throw InputError(fmt::format("{}: scene {} image {} obj_id {} is listed twice", name,
                                   t.scene_id, t.im_id, t.obj_id));
    targets.push_back(t);
  }
  return targets;
}

std::vector<TestTarget> localization_targets(int scene_id, const SceneGroundTruth& gt,
                                             const SceneGroundTruthInfo& info,
                                             double min_visib_fract) {
  std::vector<TestTarget> out;
  for (const auto& [im_id, instances] : gt) {
    const auto it = info.find(im_id);
    if (it == info.end() || it->second.size() != instances.size())
      throw InputError("scene " + std::to_string(scene_id) + ", image " + std::to_string(im_id) +
                       ": scene_gt_info.json does not list every instance of scene_gt.json");
    std::map<int, int> count;  // obj_id -> instances visible enough
    for (std::size_t i = 0; i < instances.size(); ++i)
      if (it->second[i].visib_fract >= min_visib_fract) ++count[instances[i].obj_id];
    for (const auto& [obj_id, n] : count) out.push_back({scene_id, im_id, obj_id, n});
  }
  return out;
}

namespace {

void write_json_file(const fs::path& path, const json& j) {
  write_file_atomically(path, [&](std::ostream& out) { out << j.dump(1) << "\n"; });
}

// The scene folders of dataset/test: six-digit names, in order.
std::vector<std::pair<int, fs::path>> test_scenes(const fs::path& dataset) {
  std::vector<std::pair<int, fs::path>> scenes;
  const fs::path test = dataset / "test";
  if (!fs::is_directory(test)) return scenes;
  for (const auto& e : fs::directory_iterator(test)) {
    const std::string name = e.path().filename().string();
    if (!e.is_directory() || name.size() != 6 || !std::all_of(name.begin(), name.end(), ::isdigit))
      continue;
    scenes.emplace_back(std::stoi(name), e.path());
  }
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

}  // namespace

std::size_t write_test_targets(const fs::path& dataset) {
  json bop19 = json::array(), bop24 = json::array();
  for (const auto& [scene_id, dir] : test_scenes(dataset)) {
    const SceneGroundTruth gt = read_scene_gt(dir / "scene_gt.json");
    for (const TestTarget& t : localization_targets(scene_id, gt, read_scene_gt_info(dir / "scene_gt_info.json")))
      bop19.push_back({{"im_id", t.im_id}, {"inst_count", t.inst_count}, {"obj_id", t.obj_id},
                       {"scene_id", t.scene_id}});
    for (const auto& [im_id, instances] : gt) bop24.push_back({{"im_id", im_id}, {"scene_id", scene_id}});
  }
  write_json_file(dataset / "test_targets_bop19.json", bop19);
  write_json_file(dataset / "test_targets_bop24.json", bop24);
  return bop19.size();
}

}  // namespace binpick::bop
