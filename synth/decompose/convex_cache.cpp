// Cache file layout (native little-endian; a cache is local to its machine):
//   char[8] magic "BPHULLS\0" | u32 version | u32 hull count | u64 key
//   u32 vertex count per hull | float xyz per vertex, hull after hull | u64 FNV-1a of all before
#include "synth/decompose/convex_cache.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace binpick {
namespace {

constexpr char kMagic[8] = {'B', 'P', 'H', 'U', 'L', 'L', 'S', '\0'};
// Also hashed into every key: bumped when the decomposition itself changes, so entries made
// by an older one are not served (2: flat hulls left out).
constexpr std::uint32_t kVersion = 4;  // 3: hulls merged and grown to cover the mesh; 4: max_hulls after merging
// A larger file is not one of ours; refusing it keeps a corrupt size from exhausting memory.
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{1} << 30;

class Fnv1a {
 public:
  void update(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * 0x100000001b3ULL;
  }
  template <typename T>
  void value(const T& v) {
    update(&v, sizeof v);
  }
  std::uint64_t digest() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

template <typename T>
void append(std::vector<char>& out, const T& v) {
  const auto* p = reinterpret_cast<const char*>(&v);
  out.insert(out.end(), p, p + sizeof v);
}

// Reads from a byte buffer with bounds checks; `ok` turns false on the first overrun.
class Reader {
 public:
  explicit Reader(const std::vector<char>& bytes, std::size_t end) : bytes_(bytes), end_(end) {}
  template <typename T>
  T next() {
    T v{};
    if (end_ - pos_ < sizeof v) {
      ok = false;
      return v;
    }
    std::memcpy(&v, bytes_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  std::size_t remaining() const { return end_ - pos_; }
  bool ok = true;

 private:
  const std::vector<char>& bytes_;
  std::size_t end_;
  std::size_t pos_ = 0;
};

}  // namespace

std::uint64_t decomposition_key(const Mesh& part, const DecomposeOptions& options) {
  Fnv1a h;
  h.value(kVersion);
  h.value(static_cast<std::uint64_t>(part.positions.size()));
  for (const auto& p : part.positions) h.update(p.data(), 3 * sizeof(float));
  h.value(static_cast<std::uint64_t>(part.triangles.size()));
  for (const auto& t : part.triangles) h.update(t.data(), 3 * sizeof(std::uint32_t));
  h.value(options.concavity);
  h.value(options.compacity_weight);
  h.value(options.volume_weight);
  h.value(static_cast<std::uint64_t>(options.min_clusters));
  h.value(static_cast<std::uint64_t>(options.max_hull_vertices));
  h.value(static_cast<std::uint64_t>(options.max_hulls));
  h.value(options.merge.max_added_per_merge);
  h.value(options.merge.max_added_total);
  h.value(options.max_uncovered);
  h.value(static_cast<std::uint8_t>(options.add_extra_dist_points));
  h.value(static_cast<std::uint8_t>(options.add_neighbours_dist_points));
  h.value(static_cast<std::uint8_t>(options.add_faces_points));
  h.value(static_cast<std::uint64_t>(options.max_hacd_triangles));
  h.value(static_cast<std::uint64_t>(options.hacd_target_triangles));
  return h.digest();
}

std::filesystem::path resolve_cache_dir(const std::filesystem::path& requested) {
  if (!requested.empty()) return requested;
  const auto env = [](const char* name) -> std::string {
    const char* v = std::getenv(name);
    return v ? v : "";
  };
  if (const auto dir = env("BINPICK_CACHE_DIR"); !dir.empty()) return dir;
  if (const auto xdg = env("XDG_CACHE_HOME"); !xdg.empty())
    return std::filesystem::path(xdg) / "binpick";
  if (const auto home = env("HOME"); !home.empty())
    return std::filesystem::path(home) / ".cache" / "binpick";
  return std::filesystem::temp_directory_path() / "binpick-cache";
}

std::filesystem::path cache_file(const std::filesystem::path& dir, std::uint64_t key) {
  char name[40];
  std::snprintf(name, sizeof name, "hulls-%016llx.bin", static_cast<unsigned long long>(key));
  return dir / name;
}

std::optional<ConvexParts> read_cached_parts(const std::filesystem::path& file, std::uint64_t key) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec || size > kMaxFileBytes || size < sizeof(kMagic) + sizeof(std::uint64_t)) return {};
  std::ifstream in(file, std::ios::binary);
  std::vector<char> bytes(static_cast<std::size_t>(size));
  if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) return {};

  const std::size_t body = bytes.size() - sizeof(std::uint64_t);
  Fnv1a checksum;
  checksum.update(bytes.data(), body);
  std::uint64_t stored_checksum = 0;
  std::memcpy(&stored_checksum, bytes.data() + body, sizeof stored_checksum);
  if (stored_checksum != checksum.digest()) return {};

  Reader r(bytes, body);
  char magic[8];
  for (char& c : magic) c = r.next<char>();
  const auto version = r.next<std::uint32_t>();
  const auto hull_count = r.next<std::uint32_t>();
  const auto stored_key = r.next<std::uint64_t>();
  if (!r.ok || std::memcmp(magic, kMagic, sizeof magic) != 0 || version != kVersion ||
      stored_key != key || hull_count == 0 || hull_count > r.remaining() / 4)
    return {};
  std::vector<std::uint32_t> counts(hull_count);
  std::uint64_t total_vertices = 0;
  for (auto& n : counts) total_vertices += n = r.next<std::uint32_t>();
  if (!r.ok || total_vertices * 3 * sizeof(float) != r.remaining()) return {};

  ConvexParts parts;
  parts.hulls.resize(hull_count);
  for (std::size_t h = 0; h < hull_count; ++h) {
    auto& vertices = parts.hulls[h].vertices;
    vertices.resize(counts[h]);
    for (auto& v : vertices) v = {r.next<float>(), r.next<float>(), r.next<float>()};
  }
  return parts;
}

bool write_cached_parts(const std::filesystem::path& file, std::uint64_t key,
                        const ConvexParts& parts) {
  std::vector<char> bytes(kMagic, kMagic + sizeof kMagic);
  append(bytes, kVersion);
  append(bytes, static_cast<std::uint32_t>(parts.hulls.size()));
  append(bytes, key);
  for (const auto& hull : parts.hulls)
    append(bytes, static_cast<std::uint32_t>(hull.vertices.size()));
  for (const auto& hull : parts.hulls)
    for (const auto& v : hull.vertices) {
      append(bytes, v.x());
      append(bytes, v.y());
      append(bytes, v.z());
    }
  Fnv1a checksum;
  checksum.update(bytes.data(), bytes.size());
  append(bytes, checksum.digest());

  // A reader (another process making the same dataset) sees the old file or the whole new
  // one, never a half-written one: write a unique temporary name, then rename over.
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  const auto tmp = file.parent_path() /
                   (file.filename().string() + ".tmp." + std::to_string(::getpid()) + "." +
                    std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id())));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::filesystem::remove(tmp, ec);
      spdlog::warn("cannot write the convex decomposition cache {}", tmp.string());
      return false;
    }
  }
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    spdlog::warn("cannot store the convex decomposition cache {}: {}", file.string(), ec.message());
    return false;
  }
  return true;
}

}  // namespace binpick
