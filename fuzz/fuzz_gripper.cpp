// libFuzzer target: the detect --gripper JSON file, parse_gripper_json.
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_gripper, data, size);
}
