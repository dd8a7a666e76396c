#include "host/formats/mesh/announced_triangles.hpp"

#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/formats/mesh/little_endian.hpp"
#include "host/formats/mesh/mesh_readers.hpp"
#include "host/formats/mesh/ply_header.hpp"

namespace binpick {
namespace {

std::uint64_t ply_faces(std::string_view bytes) {
  try {
    for (const auto& element : ply::parse_header(bytes).elements)
      if (element.name == "face") return element.count;
  } catch (const InputError&) {
  }
  return 0;
}

// Records that start a line with `word` followed by a blank (OBJ's "f", ascii STL's "facet").
std::uint64_t count_records(std::string_view bytes, std::string_view word) {
  std::uint64_t n = 0;
  for (std::size_t at = 0; at < bytes.size();) {
    const std::size_t start = bytes.find_first_not_of(" \t", at);
    if (start == std::string_view::npos) break;
    const std::string_view rest = bytes.substr(start);
    if (rest.starts_with(word) && rest.size() > word.size() &&
        (rest[word.size()] == ' ' || rest[word.size()] == '\t'))
      ++n;
    const std::size_t end = bytes.find('\n', start);
    if (end == std::string_view::npos) break;
    at = end + 1;
  }
  return n;
}

std::uint64_t stl_triangles(std::string_view bytes) {
  if (const auto count = binary_stl_triangles(bytes)) return *count;  // as read_stl decides
  return count_records(bytes, "facet");
}

// Triangles of every triangle primitive of every mesh (indices / 3, or vertices / 3).
std::uint64_t gltf_triangles(std::string_view bytes) {
  std::string_view text = bytes;
  if (bytes.starts_with("glTF")) {  // GLB: the JSON chunk comes first, after the 12-byte header
    if (bytes.size() < 20) return 0;
    const std::uint64_t length = load_little_endian<std::uint32_t>(bytes.data() + 12);
    if (20 + length > bytes.size()) return 0;
    text = bytes.substr(20, length);
  }
  const auto json = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!json.is_object() || !json.contains("meshes") || !json.contains("accessors")) return 0;
  const auto& accessors = json["accessors"];
  auto count_of = [&](const nlohmann::json& index) -> std::uint64_t {
    if (!index.is_number_unsigned() || index.get<std::uint64_t>() >= accessors.size()) return 0;
    const auto& accessor = accessors[index.get<std::size_t>()];
    const auto count = accessor.is_object() ? accessor.value("count", nlohmann::json()) : nullptr;
    return count.is_number_unsigned() ? count.get<std::uint64_t>() : 0;
  };
  std::uint64_t total = 0;
  if (!json["meshes"].is_array() || !accessors.is_array()) return 0;
  for (const auto& mesh : json["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
      continue;
    for (const auto& primitive : mesh["primitives"]) {
      if (!primitive.is_object()) continue;
      const auto mode = primitive.value("mode", nlohmann::json(4));
      if (mode != 4) continue;  // TRIANGLES only: the reader skips the rest
      if (primitive.contains("indices")) {
        total += count_of(primitive["indices"]) / 3;
      } else if (primitive.contains("attributes") && primitive["attributes"].is_object() &&
                 primitive["attributes"].contains("POSITION")) {
        total += count_of(primitive["attributes"]["POSITION"]) / 3;
      }
    }
  }
  return total;
}

}  // namespace

std::uint64_t announced_triangles(std::string_view bytes, std::string_view format) {
  if (format == "ply") return ply_faces(bytes);
  if (format == "stl") return stl_triangles(bytes);
  if (format == "obj") return count_records(bytes, "f");
  if (format == "gltf" || format == "glb") return gltf_triangles(bytes);
  return 0;
}

}  // namespace binpick
