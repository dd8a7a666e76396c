// libFuzzer target: BOP's scene_gt_info file, bop::read_scene_gt_info.
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_scene_gt_info, data, size);
}
