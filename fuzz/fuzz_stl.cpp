// libFuzzer target: a .stl model file through parse_model (the mesh loader from bytes).
#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return binpick::fuzz::run_one_input(binpick::fuzz::parse_stl, data, size);
}
