#include <utility>

#include "host/core/error.hpp"
#include "host/formats/mesh/mesh_writers.hpp"

namespace binpick {
namespace {

constexpr std::pair<const char*, MeshFormat> format_names[] = {
    {"ply", MeshFormat::ply}, {"ply-ascii", MeshFormat::ply_ascii}, {"stl", MeshFormat::stl},
    {"obj", MeshFormat::obj}, {"gltf", MeshFormat::gltf},           {"glb", MeshFormat::glb}};

}  // namespace

void write_mesh(const std::filesystem::path& path, const Mesh& mesh, MeshFormat format) {
  switch (format) {
    case MeshFormat::ply:
      return write_ply(path, mesh, PlyEncoding::binary_little_endian);
    case MeshFormat::ply_ascii:
      return write_ply(path, mesh, PlyEncoding::ascii);
    case MeshFormat::stl:
      return write_stl(path, mesh);
    case MeshFormat::obj:
      return write_obj(path, mesh);
    case MeshFormat::gltf:
      return write_gltf(path, mesh, false);
    case MeshFormat::glb:
      return write_gltf(path, mesh, true);
  }
}

MeshFormat mesh_format_named(const std::string& name) {
  std::string known;
  for (const auto& [format_name, format] : format_names) {
    if (name == format_name) return format;
    known += (known.empty() ? "" : ", ") + std::string(format_name);
  }
  throw InputError("unknown mesh format '" + name + "' (known: " + known + ")");
}

std::string extension_of(MeshFormat format) {
  switch (format) {
    case MeshFormat::ply:
    case MeshFormat::ply_ascii:
      return ".ply";
    case MeshFormat::stl:
      return ".stl";
    case MeshFormat::obj:
      return ".obj";
    case MeshFormat::gltf:
      return ".gltf";
    case MeshFormat::glb:
      return ".glb";
  }
  return "";
}

}  // namespace binpick
