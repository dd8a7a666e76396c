#include <cstdint>
#include <string>

#include "host/core/atomic_file.hpp"
#include "host/formats/mesh/little_endian.hpp"
#include "host/formats/mesh/mesh_writers.hpp"
#include "host/formats/mesh/text_numbers.hpp"
#include "host/core/mesh_normals.hpp"

namespace binpick {
namespace {

std::string ply_header(const Mesh& mesh, PlyEncoding encoding) {
  std::string h = "ply\nformat ";
  h += encoding == PlyEncoding::ascii ? "ascii" : "binary_little_endian";
  h += " 1.0\ncomment written by binpick, units: mm\n";
  h += "element vertex " + std::to_string(mesh.positions.size()) + "\n";
  h += "property float x\nproperty float y\nproperty float z\n";
  h += "property float nx\nproperty float ny\nproperty float nz\n";
  h += "element face " + std::to_string(mesh.triangles.size()) + "\n";
  h += "property list uchar int vertex_indices\nend_header\n";
  return h;
}

void append_binary_body(std::string& out, const Mesh& mesh) {
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    for (float v : mesh.positions[i]) append_little_endian(out, v);
    for (float v : mesh.normals[i]) append_little_endian(out, v);
  }
  for (const auto& t : mesh.triangles) {
    append_little_endian(out, std::uint8_t{3});
    for (auto v : t) append_little_endian(out, static_cast<std::int32_t>(v));
  }
}

void append_ascii_body(std::string& out, const Mesh& mesh) {
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const char* separator = "";
    for (float v : mesh.positions[i]) {
      out += separator;
      append_number(out, v);
      separator = " ";
    }
    for (float v : mesh.normals[i]) {
      out += ' ';
      append_number(out, v);
    }
    out += '\n';
  }
  for (const auto& t : mesh.triangles) {
    out += '3';
    for (auto v : t) {
      out += ' ';
      append_number(out, v);
    }
    out += '\n';
  }
}

}  // namespace

void write_ply(const std::filesystem::path& path, const Mesh& input, PlyEncoding encoding) {
  const Mesh mesh = with_normals(input);
  std::string bytes = ply_header(mesh, encoding);
  if (encoding == PlyEncoding::ascii) {
    append_ascii_body(bytes, mesh);
  } else {
    append_binary_body(bytes, mesh);
  }
  write_file_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), bytes.size()); });
}

}  // namespace binpick
