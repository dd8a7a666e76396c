// libFuzzer target: a depth (16-bit) or intensity (8-bit) PNG, read_png16 then read_png8.
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_png, data, size);
}
