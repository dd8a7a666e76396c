// libFuzzer target: BOP's target list (test_targets_bop19.json), bop::parse_test_targets.
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_test_targets, data, size);
}
