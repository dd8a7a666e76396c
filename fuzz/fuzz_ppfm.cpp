// libFuzzer target: a trained .ppfm model file, parse_ppf_model.
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_ppfm, data, size);
}
