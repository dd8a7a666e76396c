// STL, binary and ascii. The file's facet normals are ignored: exporters often leave them zero
// or inconsistent, while the vertex order (counter-clockwise from outside) is what STL readers
// rely on. The result is a triangle soup; load_model() welds it.
#include <charconv>
#include <sstream>

#include "host/core/error.hpp"
#include "host/formats/mesh/little_endian.hpp"
#include "host/formats/mesh/mesh_readers.hpp"

namespace binpick {
namespace {

constexpr std::size_t binary_header_size = 84;  // 80 bytes of text + uint32 triangle count
constexpr std::size_t binary_triangle_size = 50;

std::uint64_t declared_binary_size(std::string_view bytes) {
  const auto count = load_little_endian<std::uint32_t>(bytes.data() + 80);
  return binary_header_size + std::uint64_t{count} * binary_triangle_size;
}

Mesh read_binary_stl(std::string_view bytes) {
  const auto count = load_little_endian<std::uint32_t>(bytes.data() + 80);
  Mesh mesh;
  mesh.positions.reserve(std::size_t{count} * 3);
  mesh.triangles.reserve(count);
  for (std::uint32_t t = 0; t < count; ++t) {
    // Skip the facet normal (12 bytes); the attribute word (2 bytes) is unused.
    const char* corner = bytes.data() + binary_header_size + t * binary_triangle_size + 12;
    for (int c = 0; c < 3; ++c, corner += 12) {
      mesh.positions.emplace_back(load_little_endian<float>(corner),
                                  load_little_endian<float>(corner + 4),
                                  load_little_endian<float>(corner + 8));
    }
    mesh.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  return mesh;
}

float parse_coordinate(const std::string& word) {
  float value = 0;
  const char* first = word.data() + (word.starts_with('+') ? 1 : 0);
  auto [ptr, ec] = std::from_chars(first, word.data() + word.size(), value);
  if (ec != std::errc{} || ptr != word.data() + word.size())
    throw InputError("ascii STL: bad vertex coordinate '" + word + "'");
  return value;
}

// Only "vertex x y z" and "endloop" matter; loops of more than three vertices (which some
// exporters write) are fan-triangulated.
Mesh read_ascii_stl(std::string_view bytes) {
  std::istringstream words{std::string(bytes)};
  Mesh mesh;
  std::vector<Eigen::Vector3f> loop;
  bool ended = false;  // an "endsolid" after the last facet: the file is complete
  for (std::string word; words >> word;) {
    if (word == "endsolid") {
      ended = true;
    } else if (word == "facet") {
      ended = false;
    } else if (word == "vertex") {
      std::string x, y, z;
      if (!(words >> x >> y >> z)) throw InputError("ascii STL is truncated inside a vertex");
      loop.emplace_back(parse_coordinate(x), parse_coordinate(y), parse_coordinate(z));
    } else if (word == "endloop") {
      if (loop.size() < 3) throw InputError("ascii STL: a facet has fewer than 3 vertices");
      const auto first = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.insert(mesh.positions.end(), loop.begin(), loop.end());
      for (std::uint32_t j = 1; j + 1 < loop.size(); ++j) {
        mesh.triangles.push_back({first, first + j, first + j + 1});
      }
      loop.clear();
    }
  }
  if (!loop.empty()) throw InputError("ascii STL is truncated: a facet has no endloop");
  if (!ended) throw InputError("ascii STL is truncated: no endsolid after the last facet");
  return mesh;
}

}  // namespace

Mesh read_stl(std::string_view bytes) {
  // Binary files may also start with "solid", so the size rule decides first.
  if (binary_stl_triangles(bytes)) return read_binary_stl(bytes);
  std::size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start != std::string_view::npos && bytes.substr(start).starts_with("solid"))
    return read_ascii_stl(bytes);
  if (bytes.size() < binary_header_size)
    throw InputError("not an STL file: too short for a binary STL and not ascii ('solid')");
  const auto declared = declared_binary_size(bytes);
  if (declared > bytes.size())
    throw InputError("binary STL is truncated: its header announces " +
                     std::to_string((declared - binary_header_size) / binary_triangle_size) +
                     " triangles (" + std::to_string(declared) + " bytes) but the file has " +
                     std::to_string(bytes.size()) + " bytes");
  // Some exporters pad the file; the announced triangles are all there.
  return read_binary_stl(bytes);
}

std::optional<std::uint32_t> binary_stl_triangles(std::string_view bytes) {
  if (bytes.size() < binary_header_size || declared_binary_size(bytes) != bytes.size())
    return std::nullopt;
  return load_little_endian<std::uint32_t>(bytes.data() + 80);
}

}  // namespace binpick
