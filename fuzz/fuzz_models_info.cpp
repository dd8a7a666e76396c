// libFuzzer target: BOP's models_info file, bop::parse_models_info.
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_models_info, data, size);
}
