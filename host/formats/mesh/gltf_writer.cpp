#include <tiny_gltf.h>

#include <bit>
#include <cstring>
#include <sstream>

#include "host/core/error.hpp"
#include "host/core/atomic_file.hpp"
#include "host/formats/mesh/mesh_writers.hpp"
#include "host/core/mesh_geometry.hpp"
#include "host/core/mesh_normals.hpp"

namespace binpick {
namespace {

// Appends data to the single buffer as its own buffer view; returns the view index.
int add_buffer_view(tinygltf::Model& model, const void* data, std::size_t size, int target) {
  auto& buffer = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = size;
  view.target = target;
  buffer.resize(buffer.size() + size);
  std::memcpy(buffer.data() + view.byteOffset, data, size);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

int add_accessor(tinygltf::Model& model, int view, int component_type, int type,
                 std::size_t count) {
  tinygltf::Accessor accessor;
  accessor.bufferView = view;
  accessor.componentType = component_type;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

// One mesh, one node, one scene; little endian float and uint32 data (the host order on every
// platform binpick targets, as glTF requires).
tinygltf::Model gltf_model_of(const Mesh& mesh) {
  static_assert(std::endian::native == std::endian::little, "glTF buffers are little endian");
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "binpick (units: mm, not the metres glTF assumes)";
  model.buffers.emplace_back();
  const auto positions =
      add_buffer_view(model, mesh.positions.data(), mesh.positions.size() * sizeof(Eigen::Vector3f),
                      TINYGLTF_TARGET_ARRAY_BUFFER);
  const auto normals =
      add_buffer_view(model, mesh.normals.data(), mesh.normals.size() * sizeof(Eigen::Vector3f),
                      TINYGLTF_TARGET_ARRAY_BUFFER);
  const auto indices = add_buffer_view(model, mesh.triangles.data(),
                                       mesh.triangles.size() * sizeof(mesh.triangles[0]),
                                       TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] = add_accessor(model, positions, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                  TINYGLTF_TYPE_VEC3, mesh.positions.size());
  // The spec requires the bounds of POSITION.
  const BoundingBox box = bounding_box(mesh.positions);
  model.accessors.back().minValues = {box.min.x(), box.min.y(), box.min.z()};
  model.accessors.back().maxValues = {box.max.x(), box.max.y(), box.max.z()};
  primitive.attributes["NORMAL"] = add_accessor(model, normals, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                TINYGLTF_TYPE_VEC3, mesh.normals.size());
  primitive.indices = add_accessor(model, indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                   TINYGLTF_TYPE_SCALAR, 3 * mesh.triangles.size());
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = "part";
  gltf_mesh.primitives.push_back(primitive);
  model.meshes.push_back(gltf_mesh);
  tinygltf::Node node;
  node.name = "part";
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return model;
}

}  // namespace

void write_gltf(const std::filesystem::path& path, const Mesh& input, bool binary) {
  const Mesh mesh = with_normals(input);
  const tinygltf::Model model = gltf_model_of(mesh);
  write_file_atomically(path, [&](std::ostream& out) {
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/!binary, binary))
      throw InputError("cannot write " + path.string() + ": glTF serialisation failed");
  });
}

}  // namespace binpick
