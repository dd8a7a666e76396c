// BOP's test target lists at a dataset's root (bop_toolkit scripts/create_test_targets.py):
// test_targets_bop19.json, the localization targets (per image and object, how many of its
// instances are at least 10 % visible), and test_targets_bop24.json, the detection targets
// (every image). Written from each test/NNNNNN/scene_gt.json and scene_gt_info.json.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "host/formats/bop/bop_files.hpp"

namespace binpick::bop {

// The toolkit's default visib_gt_min: instances less visible are not targets.
inline constexpr double kTargetMinVisibFract = 0.1;

struct TestTarget {
  int scene_id = 0, im_id = 0, obj_id = 0, inst_count = 0;
};

// One scene's localization targets, by image then obj_id; objects with no instance at least
// min_visib_fract visible have none. InputError when an image's gt and gt_info lists differ.
std::vector<TestTarget> localization_targets(int scene_id, const SceneGroundTruth& gt,
                                             const SceneGroundTruthInfo& info,
                                             double min_visib_fract = kTargetMinVisibFract);

// Parses a target list's text ([{"scene_id", "im_id", "obj_id", "inst_count"}, ...]), in file
// order. InputError naming `name` and the entry for anything else, a negative id or count, or a
// repeated (scene_id, im_id, obj_id). Entries with inst_count 0 are kept (callers skip them).
std::vector<TestTarget> parse_test_targets(const std::string& text, const std::string& name);

// Reads every dataset/test/NNNNNN scene (in scene order) and writes both files at the root
// (atomically). Returns the number of localization targets.
std::size_t write_test_targets(const std::filesystem::path& dataset);

}  // namespace binpick::bop
