// libFuzzer target: the detect --bin-pose JSON file, parse_bin_pose.
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_bin_pose, data, size);
}
