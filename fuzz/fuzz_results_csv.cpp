// libFuzzer target: BOP's results_csv file, bop::parse_results_csv.
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_results_csv, data, size);
}
