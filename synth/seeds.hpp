// Independent, reproducible seeds for every bin of a dataset from the user's one --seed, so a
// bin can be made (or remade when resuming) without making the ones before it.
#pragma once

#include <cstdint>

namespace binpick {

// SplitMix64's finaliser: consecutive inputs give well-spread, independent outputs.
inline std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace binpick
