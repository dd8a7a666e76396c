#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "host/core/atomic_file.hpp"
#include "host/formats/mesh/little_endian.hpp"
#include "host/formats/mesh/mesh_writers.hpp"

namespace binpick {

void write_stl(const std::filesystem::path& path, const Mesh& mesh) {
  // The 80-byte header must not start with "solid", or readers may take the file for ascii.
  std::string bytes = "binpick binary STL, units: mm";
  bytes.resize(80, ' ');
  append_little_endian(bytes, static_cast<std::uint32_t>(mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3f& a = mesh.positions[t[0]];
    const Eigen::Vector3f& b = mesh.positions[t[1]];
    const Eigen::Vector3f& c = mesh.positions[t[2]];
    const Eigen::Vector3f normal = (b - a).cross(c - a).normalized();
    for (float v : normal) append_little_endian(bytes, v);
    for (const auto* p : {&a, &b, &c}) {
      for (float v : *p) append_little_endian(bytes, v);
    }
    append_little_endian(bytes, std::uint16_t{0});
  }
  write_file_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), bytes.size()); });
}

}  // namespace binpick
