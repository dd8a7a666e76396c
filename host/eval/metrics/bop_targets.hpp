// BOP's estimation targets (test_targets_bop19.json: per image and obj_id the number of instances
// to find, inst_count) and which ground-truth instances count as targets, as the toolkit's
// eval_bop19_pose.py sets it up (visib_gt_min = -1 in eval_calc_scores.py: per image and obj_id
// the inst_count most visible instances, by visib_fract).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "host/eval/metrics/eval_dataset.hpp"

namespace binpick::eval {

// Per image, obj_id -> inst_count (> 0).
using BopTargets = std::map<ImageKey, std::map<int, int>>;

// BOP's rule for the targets it publishes: the instances with visib_fract >= 0.1.
inline constexpr double kBopTargetVisibility = 0.1;

struct TargetSet {
  BopTargets targets;
  std::string source;  // the file read (its name, in the dataset root), or how they were derived
};

// Parses test_targets_bop19.json text ([{"scene_id", "im_id", "obj_id", "inst_count"}, ...]).
// Throws InputError naming `name` for anything else, a negative id or count, or a repeated
// (scene_id, im_id, obj_id). Entries with inst_count 0 are dropped.
BopTargets parse_bop_targets(const std::string& text, const std::string& name);

// The dataset's root/test_targets_bop19.json if it has one (InputError if it names an image the
// dataset lacks or an obj_id models_info.json lacks); else, per image, the instances of each obj_id with visib_fract >= 0.1 (every
// instance if the scene has no scene_gt_info.json).
TargetSet bop_targets(const Dataset& dataset);

// Which ground-truth instances of the image are targets: of each obj_id with an inst_count, the
// inst_count instances with the largest visib_fract (the first on ties; every instance counts
// as fully visible without scene_gt_info.json). Indexed like image.gt.
std::vector<bool> target_instances(const EvalImage& image, const std::map<int, int>& inst_count);

}  // namespace binpick::eval
