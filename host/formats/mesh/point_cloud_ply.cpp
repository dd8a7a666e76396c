#include "host/formats/mesh/point_cloud_ply.hpp"

#include <string>

#include "host/core/error.hpp"
#include "host/core/atomic_file.hpp"
#include "host/formats/mesh/little_endian.hpp"
#include "host/core/read_file.hpp"
#include "host/formats/mesh/mesh_readers.hpp"

namespace binpick {

void write_point_cloud_ply(const std::filesystem::path& path, const PointCloud& cloud) {
  const bool with_normals = !cloud.normals.empty();
  if (with_normals && cloud.normals.size() != cloud.points.size())
    throw InputError("cannot write " + path.string() + ": point and normal counts differ");
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\ncomment written by binpick, units: mm\n";
  bytes += "element vertex " + std::to_string(cloud.points.size()) + "\n";
  bytes += "property float x\nproperty float y\nproperty float z\n";
  if (with_normals) bytes += "property float nx\nproperty float ny\nproperty float nz\n";
  bytes += "end_header\n";
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    for (float v : cloud.points[i]) append_little_endian(bytes, v);
    if (with_normals) {
      for (float v : cloud.normals[i]) append_little_endian(bytes, v);
    }
  }
  write_file_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), bytes.size()); });
}

PointCloud read_point_cloud_ply(const std::filesystem::path& path) {
  Mesh mesh;
  try {
    mesh = read_ply(read_file_bytes(path));
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (message.starts_with(path.string())) throw;
    throw InputError(path.string() + ": " + message);
  }
  for (const auto& p : mesh.positions) {
    if (!p.allFinite())
      throw InputError(path.string() + ": a point has a NaN or infinite coordinate");
  }
  return {std::move(mesh.positions), std::move(mesh.normals)};
}

}  // namespace binpick
