// The parsers of outside data (files a user or another tool hands binpick), each as a function
// of raw bytes. The same functions serve the libFuzzer targets (fuzz/fuzz_NAME.cpp, built with
// -DBINPICK_FUZZ=ON) and the corpus replay test (tests/formats/test_fuzz_corpus.cpp): each input
// either parses or is rejected with binpick::InputError; anything else is a bug.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace binpick::fuzz {

// Parses bytes as one kind of file; returns if they parse, throws InputError if they do not.
using Parse = void (*)(std::string_view bytes);

void parse_ply(std::string_view bytes);           // model through parse_model, format "ply"
void parse_stl(std::string_view bytes);           // ... "stl"
void parse_obj(std::string_view bytes);           // ... "obj"
void parse_gltf(std::string_view bytes);          // ... "gltf" (.gltf text or GLB binary)
void parse_ppfm(std::string_view bytes);          // parse_ppf_model
void parse_camera(std::string_view bytes);        // bop::read_camera
void parse_scene_camera(std::string_view bytes);  // bop::read_scene_cameras
void parse_scene_gt(std::string_view bytes);      // bop::read_scene_gt
void parse_scene_gt_info(std::string_view bytes); // bop::read_scene_gt_info
void parse_models_info(std::string_view bytes);   // bop::parse_models_info
void parse_png(std::string_view bytes);           // read_png16, then read_png8
void parse_results_csv(std::string_view bytes);   // bop::parse_results_csv
void parse_params(std::string_view bytes);        // apply_params_file (detect --params)
void parse_bin_pose(std::string_view bytes);      // parse_bin_pose (detect --bin-pose)
void parse_grasps(std::string_view bytes);        // parse_grasps_json (train/detect --grasps)
void parse_gripper(std::string_view bytes);       // parse_gripper_json (detect --gripper FILE)
void parse_test_targets(std::string_view bytes);  // bop::parse_test_targets (detect --targets, eval)

struct Target {
  const char* name;  // fuzz/corpus/NAME, fuzz/regressions/NAME, the executable fuzz_NAME
  Parse parse;
};

// Every target, in a fixed order.
const std::vector<Target>& all_targets();

// The body of LLVMFuzzerTestOneInput: parse, and accept an InputError (a rejected input);
// any other exception escapes and libFuzzer reports it as a crash.
int run_one_input(Parse parse, const std::uint8_t* data, std::size_t size);

}  // namespace binpick::fuzz
