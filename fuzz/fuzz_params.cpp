// libFuzzer target: the detect --params JSON file, apply_params_file and its roi/bin texts.
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_params, data, size);
}
