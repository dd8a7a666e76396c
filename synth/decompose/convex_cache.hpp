// On-disk cache of convex decompositions, keyed by a hash of the mesh and the options.
// HACD takes seconds on a detailed CAD part; every bin of a dataset needs the same hulls.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "host/core/mesh.hpp"
#include "synth/decompose/convex_parts.hpp"
#include "synth/decompose/decompose.hpp"

namespace binpick {

// 64-bit FNV-1a over the raw vertex and index bytes and every option that changes the result
// (not the cache location). Bumped with the file format version, so old entries are ignored.
std::uint64_t decomposition_key(const Mesh& part, const DecomposeOptions& options);

// `requested` if not empty, else $BINPICK_CACHE_DIR, $XDG_CACHE_HOME/binpick, ~/.cache/binpick,
// and as a last resort the system's temporary directory.
std::filesystem::path resolve_cache_dir(const std::filesystem::path& requested);

// The file of one key inside `dir`.
std::filesystem::path cache_file(const std::filesystem::path& dir, std::uint64_t key);

// The hulls stored in `file` under `key`; nullopt when the file is missing, truncated, corrupt,
// of another format version or of another key.
std::optional<ConvexParts> read_cached_parts(const std::filesystem::path& file, std::uint64_t key);

// Writes atomically (a temporary file renamed over the target), creating the directory.
// Returns false instead of throwing: the cache is an optimisation, a read-only disk is not fatal.
bool write_cached_parts(const std::filesystem::path& file, std::uint64_t key,
                        const ConvexParts& parts);

}  // namespace binpick
