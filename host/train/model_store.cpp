#include "host/train/model_store.hpp"

#include <chrono>
#include <cstdint>
#include <cstring>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/atomic_file.hpp"
#include "host/core/read_file.hpp"
#include "host/train/ppf_model_file.hpp"
#include "host/core/timing.hpp"

namespace binpick {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

class Fnv64 {
 public:
  void add(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) h_ = (h_ ^ p[i]) * 1099511628211ull;
  }
  std::string hex() const { return fmt::format("{:016x}", h_); }

 private:
  std::uint64_t h_ = 1469598103934665603ull;
};

// The mesh as loaded (after scaling): a file edited in place gets a new checksum.
std::string mesh_checksum(const Mesh& mesh) {
  Fnv64 h;
  for (const auto& p : mesh.positions) h.add(p.data(), 3 * sizeof(float));
  for (const auto& t : mesh.triangles) h.add(t.data(), 3 * sizeof(std::uint32_t));
  return h.hex();
}

json inputs_record(const Mesh& mesh, const std::string& part, const PpfTrainParams& p) {
  return {{"part", part},
          {"mesh_checksum", mesh_checksum(mesh)},
          {"voxel_ratio", p.voxel_ratio},
          {"distance_steps", p.distance_steps},
          {"angle_steps", p.angle_steps},
          {"format_version", kPpfModelFormatVersion}};
}

fs::path record_path(const fs::path& model) { return fs::path(model.string() + ".json"); }

// The model in `path` if its record says it was made from `inputs` and the bytes still match
// the checksum recorded; nothing otherwise (a stale or damaged model is simply retrained).
bool try_reuse(const fs::path& path, const json& inputs, TrainedModel& out) {
  if (!fs::is_regular_file(path) || !fs::is_regular_file(record_path(path))) return false;
  json record;
  try {
    record = json::parse(read_file_bytes(record_path(path)));
  } catch (const json::exception&) {
    return false;
  }
  if (!record.is_object() || record.value("inputs", json()) != inputs) return false;
  const std::string bytes = read_file_bytes(path);
  if (record.value("model_checksum", std::string()) != checksum_hex(bytes)) return false;
  out.model = parse_ppf_model(bytes, path.string());
  out.checksum = checksum_hex(bytes);
  out.reused = true;
  return true;
}

}  // namespace

std::string describe(const PartSpec& part) {
  std::string d = part.spec;
  if (part.options.unit_scale != 1.0) d += fmt::format(" unit-scale {}", part.options.unit_scale);
  if (part.options.diameter) d += fmt::format(" diameter {}", *part.options.diameter);
  if (!part.options.mesh_name.empty()) d += " mesh " + part.options.mesh_name;
  return d;
}

std::string checksum_hex(std::string_view bytes) {
  Fnv64 h;
  h.add(bytes.data(), bytes.size());
  return h.hex();
}

TrainedModel train_or_reuse(const Mesh& mesh, const std::string& part_description,
                            const PpfTrainParams& params, const fs::path& path) {
  check_train_params(params);
  const auto start = std::chrono::steady_clock::now();
  const json inputs = inputs_record(mesh, part_description, params);
  TrainedModel out;
  out.path = path;
  if (try_reuse(path, inputs, out)) {
    out.seconds = seconds_since(start);
    return out;
  }
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  out.model = train_ppf_model(mesh, params, &out.stats);
  const std::string bytes = serialize_ppf_model(out.model);
  write_file_atomically(path, [&](std::ostream& s) { s << bytes; });
  out.checksum = checksum_hex(bytes);
  const json record = {{"inputs", inputs}, {"model_checksum", out.checksum}};
  write_file_atomically(record_path(path), [&](std::ostream& s) { s << record.dump(1) << "\n"; });
  out.seconds = seconds_since(start);
  return out;
}

}  // namespace binpick
