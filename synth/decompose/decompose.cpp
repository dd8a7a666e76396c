// The cached entry point: look the decomposition up by content hash, else run HACD and store.
#include "synth/decompose/decompose.hpp"

#include <spdlog/spdlog.h>

#include "synth/decompose/convex_cache.hpp"

namespace binpick {

ConvexParts decompose_convex(const Mesh& part, const DecomposeOptions& options) {
  if (!options.use_cache) return decompose_convex_uncached(part, options);

  const std::uint64_t key = decomposition_key(part, options);
  const auto file = cache_file(resolve_cache_dir(options.cache_dir), key);
  if (auto cached = read_cached_parts(file, key)) {
    spdlog::debug("convex decomposition from cache {}", file.string());
    return std::move(*cached);
  }
  if (std::filesystem::exists(file))
    spdlog::warn("ignoring unreadable convex decomposition cache {}", file.string());

  ConvexParts parts = decompose_convex_uncached(part, options);
  if (write_cached_parts(file, key, parts))
    spdlog::debug("convex decomposition stored in {}", file.string());
  return parts;
}

}  // namespace binpick
