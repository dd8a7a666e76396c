// Chunked scans over the pixels of an image: work item g handles [g * size, (g + 1) * size).
// The chunk kernels (argmin, compaction) scan their chunk in order, which makes ties and the
// compacted order deterministic; a few hundred chunks keep both CPU cores busy.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace binpick {

struct Chunks {
  std::uint32_t count = 0;  // work items; 0 for an empty image
  std::uint32_t size = 0;   // pixels per work item
};

inline Chunks chunks_for(std::size_t n, std::size_t max_chunks = 512) {
  if (n == 0) return {};
  const std::size_t size = (n + max_chunks - 1) / max_chunks;
  return {std::uint32_t((n + size - 1) / size), std::uint32_t(size)};
}

}  // namespace binpick
