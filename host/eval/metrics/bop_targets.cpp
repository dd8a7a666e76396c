#include "host/eval/metrics/bop_targets.hpp"

#include <algorithm>
#include <numeric>
#include <set>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"

namespace binpick::eval {
namespace {

constexpr const char* kTargetsFile = "test_targets_bop19.json";

int non_negative_int(const nlohmann::json& entry, const char* key, const std::string& name,
                     std::size_t index) {
  const auto it = entry.find(key);
  if (it == entry.end() || !it->is_number_integer() || it->get<long long>() < 0 ||
      it->get<long long>() > 1'000'000'000)
    throw InputError(fmt::format("{}: entry {} has no non-negative integer \"{}\"", name,
                                 index, key));
  return static_cast<int>(it->get<long long>());
}

double visibility(const EvalImage& image, std::size_t i) {
  return image.visib_fract.empty() ? 1.0 : image.visib_fract[i];
}

}  // namespace

BopTargets parse_bop_targets(const std::string& text, const std::string& name) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(name + " is not valid JSON: " + e.what());
  }
  if (!j.is_array()) throw InputError(name + " is not a JSON array of targets");
  BopTargets targets;
  std::set<std::tuple<int, int, int>> seen;
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_object()) throw InputError(fmt::format("{}: entry {} is not an object", name, i));
    const int scene = non_negative_int(j[i], "scene_id", name, i);
    const int im = non_negative_int(j[i], "im_id", name, i);
    const int obj = non_negative_int(j[i], "obj_id", name, i);
    const int count = non_negative_int(j[i], "inst_count", name, i);
    if (!seen.insert({scene, im, obj}).second)
      throw InputError(fmt::format("{}: scene {} image {} obj_id {} is listed twice", name,
                                   scene, im, obj));
    if (count > 0) targets[{scene, im}][obj] = count;
  }
  return targets;
}

TargetSet bop_targets(const Dataset& dataset) {
  const auto path = dataset.root / kTargetsFile;
  if (std::filesystem::exists(path)) {
    // The source relative to the dataset: report.json then reads the same wherever it lies.
    TargetSet set{parse_bop_targets(read_file_bytes(path), path.string()),
                  path.filename().string()};
    for (const auto& [key, objects] : set.targets) {
      if (!dataset.images.count(key))
        throw InputError(fmt::format("{}: scene {} image {} is not in the dataset's ground truth",
                                     path.string(), key.scene_id, key.im_id));
      for (const auto& [obj_id, count] : objects)
        if (!dataset.models.count(obj_id))
          throw InputError(fmt::format("{}: obj_id {}, which models_info.json lacks",
                                       path.string(), obj_id));
    }
    return set;
  }
  TargetSet set{{}, fmt::format("instances with visib_fract >= {}", kBopTargetVisibility)};
  for (const auto& [key, image] : dataset.images)
    for (std::size_t i = 0; i < image.gt.size(); ++i)
      if (visibility(image, i) >= kBopTargetVisibility) ++set.targets[key][image.gt[i].obj_id];
  return set;
}

std::vector<bool> target_instances(const EvalImage& image, const std::map<int, int>& inst_count) {
  std::vector<std::size_t> order(image.gt.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return visibility(image, a) > visibility(image, b);
  });
  std::map<int, int> to_add = inst_count;
  std::vector<bool> target(image.gt.size(), false);
  for (std::size_t i : order) {
    const auto it = to_add.find(image.gt[i].obj_id);
    if (it != to_add.end() && it->second > 0) {
      target[i] = true;
      --it->second;
    }
  }
  return target;
}

}  // namespace binpick::eval
