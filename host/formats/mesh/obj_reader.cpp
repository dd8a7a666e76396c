// Wavefront OBJ through tinyobjloader. Faces are read untriangulated and fan-triangulated here
// after their indices are checked: tinyobjloader's own triangulation reads vertex positions
// through unchecked indices.
#include <tiny_obj_loader.h>

#include <map>
#include <sstream>
#include <utility>

#include "host/core/error.hpp"
#include "host/formats/mesh/mesh_readers.hpp"

namespace binpick {

Mesh read_obj(std::string_view bytes, const std::filesystem::path& directory) {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warnings, errors;
  std::istringstream stream{std::string(bytes)};
  tinyobj::MaterialFileReader material_reader(directory.empty() ? "." : directory.string());
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &stream, &material_reader,
                        /*triangulate=*/false)) {
    throw InputError("OBJ: " + (errors.empty() ? std::string("cannot be parsed") : errors));
  }
  const std::size_t position_count = attrib.vertices.size() / 3;
  const std::size_t normal_count = attrib.normals.size() / 3;

  // One mesh vertex per distinct (position, normal) pair used by the faces.
  Mesh mesh;
  std::map<std::pair<int, int>, std::uint32_t> vertex_of;
  bool every_corner_has_normal = true;
  std::vector<std::uint32_t> polygon;
  for (const auto& shape : shapes) {
    std::size_t next_index = 0;
    for (const unsigned corners : shape.mesh.num_face_vertices) {
      polygon.clear();
      for (unsigned c = 0; c < corners; ++c) {
        if (next_index >= shape.mesh.indices.size()) throw InputError("OBJ: malformed face list");
        const auto& index = shape.mesh.indices[next_index++];
        if (index.vertex_index < 0 ||
            static_cast<std::size_t>(index.vertex_index) >= position_count)
          throw InputError("OBJ: face refers to vertex " + std::to_string(index.vertex_index + 1) +
                           " but the file has " + std::to_string(position_count) + " vertices");
        int normal = index.normal_index;
        if (normal >= 0 && static_cast<std::size_t>(normal) >= normal_count)
          throw InputError("OBJ: face refers to normal " + std::to_string(normal + 1) +
                           " but the file has " + std::to_string(normal_count) + " normals");
        if (normal < 0) every_corner_has_normal = false;
        auto [it, inserted] = vertex_of.emplace(std::pair{index.vertex_index, normal},
                                                static_cast<std::uint32_t>(mesh.positions.size()));
        if (inserted) {
          const float* p = &attrib.vertices[3 * index.vertex_index];
          mesh.positions.emplace_back(p[0], p[1], p[2]);
          const float* n = normal >= 0 ? &attrib.normals[3 * normal] : nullptr;
          mesh.normals.push_back(n ? Eigen::Vector3f(n[0], n[1], n[2]) : Eigen::Vector3f::Zero());
        }
        polygon.push_back(it->second);
      }
      for (std::size_t j = 1; j + 1 < polygon.size(); ++j) {
        mesh.triangles.push_back({polygon[0], polygon[j], polygon[j + 1]});
      }
    }
  }
  // Normals on only some corners are as good as none: load_model() computes them all.
  if (!every_corner_has_normal) mesh.normals.clear();
  return mesh;
}

}  // namespace binpick
