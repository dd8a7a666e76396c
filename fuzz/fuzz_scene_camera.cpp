// libFuzzer target: BOP's scene_camera file, bop::read_scene_cameras.
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_scene_camera, data, size);
}
