// detect --targets FILE: BOP's target list (test_targets_bop19.json: per scene, image and obj_id
// the number of instances to find, inst_count) as detection's instance budget. BOP evaluates
// only the targets, and a method is run on the target images with, per image and object, the
// inst_count best poses: so each model detects only in the images that list its obj_id, with
// that image's inst_count as its --instances budget, and images listing none of the models are
// not read at all.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>

namespace binpick {

struct DetectTargets {
  std::filesystem::path file;
  std::string checksum;  // of the file's bytes: part of the batch's fingerprint
  // (scene_id, im_id, obj_id) -> inst_count, in [1, 1000] (entries with 0 are dropped).
  std::map<std::tuple<int, int, int>, std::uint32_t> inst_count;

  // The budget of obj_id in that image; 0: not a target there.
  std::uint32_t count(int scene_id, int im_id, int obj_id) const;
};

// Reads and checks FILE (InputError naming it and the entry for anything that is not BOP's
// target list, a repeated entry, or an inst_count above detection's 1000).
DetectTargets read_detect_targets(const std::filesystem::path& file);

}  // namespace binpick
