#include "host/eval/metrics/bop_targets.hpp"

#include <algorithm>
#include <numeric>
#include <set>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/formats/bop/test_targets.hpp"

namespace binpick::eval {
namespace {

constexpr const char* kTargetsFile = "test_targets_bop19.json";

double visibility(const EvalImage& image, std::size_t i) {
  return image.visib_fract.empty() ? 1.0 : image.visib_fract[i];
}

}  // namespace

BopTargets parse_bop_targets(const std::string& text, const std::string& name) {
  BopTargets targets;
  for (const bop::TestTarget& t : bop::parse_test_targets(text, name))
    if (t.inst_count > 0) targets[{t.scene_id, t.im_id}][t.obj_id] = t.inst_count;
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
