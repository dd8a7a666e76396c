// libFuzzer target: the train/detect --grasps JSON file, parse_grasps_json.
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_grasps, data, size);
}
