#include <string>

#include "host/core/atomic_file.hpp"
#include "host/formats/mesh/mesh_writers.hpp"
#include "host/formats/mesh/text_numbers.hpp"
#include "host/core/mesh_normals.hpp"

namespace binpick {
namespace {

void append_line(std::string& out, const char* tag, const Eigen::Vector3f& v) {
  out += tag;
  for (float x : v) {
    out += ' ';
    append_number(out, x);
  }
  out += '\n';
}

}  // namespace

void write_obj(const std::filesystem::path& path, const Mesh& input) {
  const Mesh mesh = with_normals(input);
  std::string text = "# written by binpick, units: mm\n";
  for (const auto& p : mesh.positions) append_line(text, "v", p);
  for (const auto& n : mesh.normals) append_line(text, "vn", n);
  for (const auto& t : mesh.triangles) {
    text += 'f';
    for (auto v : t) {
      // OBJ indices start at 1; position and normal indices are the same here.
      const std::string index = std::to_string(v + 1);
      text += ' ' + index + "//" + index;
    }
    text += '\n';
  }
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace binpick
