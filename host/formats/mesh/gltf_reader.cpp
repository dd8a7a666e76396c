// glTF 2.0 through tinygltf: the node hierarchy (matrices or translation/rotation/scale) places
// each mesh; only triangle primitives are read. Images are never decoded.
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>
#include <set>
#include <utility>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/formats/mesh/little_endian.hpp"
#include "host/formats/mesh/gltf_accessors.hpp"
#include "host/formats/mesh/mesh_readers.hpp"

namespace binpick {
namespace {

using Transform = Eigen::Matrix4d;

struct MeshInstance {
  int mesh;
  Transform world;
};

// tinygltf decodes images through this callback; textures do not matter for a part's shape.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
  return true;
}

// External buffers (a "uri" that is not a data URI) are read through these instead of
// tinygltf's own file functions: those take the size a stream reports, so a URI naming a
// directory asked for 2^63 bytes (found by fuzzing), and they expand paths with wordexp. Here
// only regular files are read, and paths are taken as they are.
bool regular_file_exists(const std::string& path, void*) {
  std::error_code ignored;
  return std::filesystem::is_regular_file(path, ignored);
}

std::string path_as_given(const std::string& path, void*) { return path; }

bool read_buffer_file(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                      void*) {
  if (!regular_file_exists(path, nullptr)) {
    if (err) *err += "glTF buffer '" + path + "' is not a readable file\n";
    return false;
  }
  try {
    const std::string bytes = read_file_bytes(path);
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const std::exception& e) {
    if (err) *err += std::string(e.what()) + "\n";
    return false;
  }
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&,
                  void*) {
  if (err) *err += "the glTF reader writes no file\n";
  return false;
}

// tinygltf trusts the GLB chunk lengths; check them against the file first.
void check_glb_layout(std::string_view bytes) {
  auto u32 = [&](std::uint64_t offset) {
    return load_little_endian<std::uint32_t>(bytes.data() + offset);
  };
  if (bytes.size() < 20) throw InputError("GLB is truncated (shorter than its header)");
  if (u32(4) != 2) throw InputError("GLB version " + std::to_string(u32(4)) + " is not 2");
  if (u32(8) > bytes.size())
    throw InputError("GLB is truncated: header says " + std::to_string(u32(8)) +
                     " bytes, file has " + std::to_string(bytes.size()));
  std::uint64_t offset = 12;
  while (offset + 8 <= u32(8)) {
    const std::uint64_t chunk_end = offset + 8 + std::uint64_t{u32(offset)};
    if (chunk_end > u32(8)) throw InputError("GLB is truncated inside a chunk");
    offset = chunk_end;
  }
}

Transform local_transform(const tinygltf::Node& node) {
  Transform m = Transform::Identity();
  if (node.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i) m(i % 4, i / 4) = node.matrix[i];  // column-major
    return m;
  }
  Eigen::Affine3d trs = Eigen::Affine3d::Identity();
  if (node.translation.size() == 3)
    trs.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
  if (node.rotation.size() == 4)  // glTF stores x, y, z, w
    trs.rotate(
        Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2])
            .normalized());
  if (node.scale.size() == 3)
    trs.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
  return trs.matrix();
}

void check_node_index(const tinygltf::Model& model, int node) {
  if (node < 0 || static_cast<std::size_t>(node) >= model.nodes.size())
    throw InputError("glTF refers to node " + std::to_string(node) + " which does not exist");
}

// Mesh instances of the subtree at node (iteratively: the depth comes from the file). A node
// reached twice means a cycle or a shared child, which glTF forbids.
void collect_instances(const tinygltf::Model& model, int node, const Transform& parent,
                       std::set<int>& visited, std::vector<MeshInstance>& out) {
  std::vector<std::pair<int, Transform>> pending{{node, parent}};
  while (!pending.empty()) {
    auto [current, above] = pending.back();
    pending.pop_back();
    check_node_index(model, current);
    if (!visited.insert(current).second) throw InputError("glTF node hierarchy is not a tree");
    const auto& n = model.nodes[current];
    const Transform world = above * local_transform(n);
    if (n.mesh >= 0) out.push_back({n.mesh, world});
    for (auto child = n.children.rbegin(); child != n.children.rend(); ++child)
      pending.emplace_back(*child, world);
  }
}

std::vector<int> parents_of(const tinygltf::Model& model) {
  std::vector<int> parent(model.nodes.size(), -1);
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    for (int child : model.nodes[i].children) {
      check_node_index(model, child);
      parent[child] = static_cast<int>(i);
    }
  }
  return parent;
}

Transform world_transform(const tinygltf::Model& model, const std::vector<int>& parent, int node) {
  Transform world = Transform::Identity();
  for (std::size_t depth = 0; node >= 0; node = parent[node], ++depth) {
    if (depth > model.nodes.size()) throw InputError("glTF node hierarchy has a cycle");
    world = local_transform(model.nodes[node]) * world;
  }
  return world;
}

std::vector<int> root_nodes(const tinygltf::Model& model, const std::vector<int>& parent) {
  if (!model.scenes.empty()) {
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (static_cast<std::size_t>(scene) >= model.scenes.size())
      throw InputError("glTF default scene does not exist");
    return model.scenes[scene].nodes;
  }
  std::vector<int> roots;
  for (std::size_t i = 0; i < parent.size(); ++i) {
    if (parent[i] < 0) roots.push_back(static_cast<int>(i));
  }
  return roots;
}

// The named nodes and meshes, for the message about an unknown --mesh (capped: assemblies can
// have thousands of nodes).
std::string available_names(const tinygltf::Model& model) {
  auto join = [](const auto& items) {
    constexpr std::size_t shown = 40;
    std::string text;
    std::size_t named = 0;
    for (const auto& item : items) {
      if (item.name.empty()) continue;
      if (named++ < shown) text += (text.empty() ? "" : ", ") + item.name;
    }
    if (named > shown) text += ", ... (" + std::to_string(named) + " in all)";
    return text.empty() ? std::string("(none named)") : text;
  };
  return "nodes: " + join(model.nodes) + "; meshes: " + join(model.meshes);
}

// The instances to read: everything in the default scene, or the node / mesh called name.
std::vector<MeshInstance> select_instances(const tinygltf::Model& model, const std::string& name) {
  const auto parent = parents_of(model);
  std::vector<MeshInstance> instances;
  std::set<int> visited;
  if (name.empty()) {
    for (int root : root_nodes(model, parent)) {
      collect_instances(model, root, Transform::Identity(), visited, instances);
    }
    // A file of bare meshes without nodes still describes a part.
    if (model.nodes.empty()) {
      for (std::size_t m = 0; m < model.meshes.size(); ++m)
        instances.push_back({static_cast<int>(m), Transform::Identity()});
    }
    return instances;
  }
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    if (model.nodes[i].name != name) continue;
    const int node = static_cast<int>(i);
    const Transform above =
        parent[node] >= 0 ? world_transform(model, parent, parent[node]) : Transform::Identity();
    collect_instances(model, node, above, visited, instances);
    return instances;
  }
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    if (model.meshes[m].name != name) continue;
    // The mesh as placed by its first node, so a unit scale on a parent node still applies.
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
      if (model.nodes[i].mesh == static_cast<int>(m))
        return {{static_cast<int>(m), world_transform(model, parent, static_cast<int>(i))}};
    }
    return {{static_cast<int>(m), Transform::Identity()}};
  }
  throw InputError("glTF has no node or mesh named '" + name + "' (" + available_names(model) +
                   ")");
}

std::vector<std::uint32_t> triangle_list(int mode, const std::vector<std::uint32_t>& index) {
  std::vector<std::uint32_t> list;
  if (mode == TINYGLTF_MODE_TRIANGLES || mode == -1) {
    list = index;
    list.resize(index.size() - index.size() % 3);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t i = 0; i + 2 < index.size(); ++i) {
      // Every other strip triangle is reversed to keep one winding.
      if (i % 2 == 0)
        list.insert(list.end(), {index[i], index[i + 1], index[i + 2]});
      else
        list.insert(list.end(), {index[i + 1], index[i], index[i + 2]});
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (std::size_t i = 1; i + 1 < index.size(); ++i)
      list.insert(list.end(), {index[0], index[i], index[i + 1]});
  }
  return list;  // points and lines have no surface
}

// Appends one primitive placed by world; normals_complete turns false if it has no normals.
void append_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                      const Transform& world, Mesh& mesh, bool& normals_complete) {
  auto position = primitive.attributes.find("POSITION");
  if (position == primitive.attributes.end()) return;
  const auto positions = gltf::read_vec3(model, position->second);
  std::vector<std::uint32_t> index;
  if (primitive.indices >= 0) {
    index = gltf::read_indices(model, primitive.indices);
  } else {
    for (std::uint32_t i = 0; i < positions.size(); ++i) index.push_back(i);
  }
  const auto list = triangle_list(primitive.mode, index);
  if (list.empty()) return;

  const Eigen::Matrix3d linear = world.topLeftCorner<3, 3>();
  const Eigen::Matrix3d normal_matrix = linear.inverse().transpose();
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  for (const auto& p : positions)
    mesh.positions.push_back(
        (linear * p.cast<double>() + world.topRightCorner<3, 1>()).cast<float>());
  auto normal = primitive.attributes.find("NORMAL");
  if (normal != primitive.attributes.end() && normals_complete) {
    const auto normals = gltf::read_vec3(model, normal->second);
    if (normals.size() != positions.size())
      throw InputError("glTF NORMAL and POSITION counts differ");
    for (const auto& n : normals)
      mesh.normals.push_back((normal_matrix * n.cast<double>()).cast<float>());
  } else {
    normals_complete = false;
  }
  // A mirroring transform turns counter-clockwise faces clockwise (glTF spec, 3.7.4).
  const bool mirrored = linear.determinant() < 0;
  for (std::size_t t = 0; t + 2 < list.size(); t += 3) {
    for (std::size_t c = 0; c < 3; ++c) {
      if (list[t + c] >= positions.size())
        throw InputError("glTF index " + std::to_string(list[t + c]) + " is out of range (" +
                         std::to_string(positions.size()) + " vertices)");
    }
    if (mirrored)
      mesh.triangles.push_back({first + list[t], first + list[t + 2], first + list[t + 1]});
    else
      mesh.triangles.push_back({first + list[t], first + list[t + 1], first + list[t + 2]});
  }
}

}  // namespace

Mesh read_gltf(std::string_view bytes, const std::filesystem::path& directory,
               const std::string& mesh_name) {
  const bool binary = bytes.starts_with("glTF");
  if (binary) check_glb_layout(bytes);
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skip_image, nullptr);
  loader.SetFsCallbacks(
      {&regular_file_exists, &path_as_given, &read_buffer_file, &refuse_write, nullptr});
  tinygltf::Model model;
  std::string errors, warnings;
  if (bytes.size() > std::numeric_limits<unsigned>::max())
    throw InputError("glTF file is too large");
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&model, &errors, &warnings,
                                           reinterpret_cast<const unsigned char*>(bytes.data()),
                                           static_cast<unsigned>(bytes.size()), directory.string())
             : loader.LoadASCIIFromString(&model, &errors, &warnings, bytes.data(),
                                          static_cast<unsigned>(bytes.size()), directory.string());
  if (!ok) throw InputError("glTF: " + (errors.empty() ? std::string("cannot be parsed") : errors));

  // Compressed geometry would otherwise surface as a confusing accessor error.
  for (const auto& extension : model.extensionsRequired) {
    if (extension == "KHR_draco_mesh_compression" || extension == "KHR_mesh_quantization" ||
        extension == "EXT_meshopt_compression")
      throw InputError("glTF uses " + extension +
                       ", which binpick does not read; export the model uncompressed");
  }
  Mesh mesh;
  bool normals_complete = true;
  for (const auto& instance : select_instances(model, mesh_name)) {
    if (instance.mesh < 0 || static_cast<std::size_t>(instance.mesh) >= model.meshes.size())
      throw InputError("glTF refers to mesh " + std::to_string(instance.mesh) +
                       " which does not exist");
    for (const auto& primitive : model.meshes[instance.mesh].primitives)
      append_primitive(model, primitive, instance.world, mesh, normals_complete);
  }
  if (!normals_complete) mesh.normals.clear();
  return mesh;
}

}  // namespace binpick
