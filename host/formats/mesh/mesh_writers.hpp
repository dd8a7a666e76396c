// Mesh files in every format the loaders read. All writes are atomic (write_file_atomically):
// a failure leaves no partial file. Meshes without normals get crease normals computed first
// where the format stores normals.
#pragma once

#include <filesystem>
#include <string>

#include "host/core/mesh.hpp"

namespace binpick {

enum class MeshFormat { ply, ply_ascii, stl, obj, gltf, glb };

enum class PlyEncoding { binary_little_endian, ascii };

// PLY with vertex x y z nx ny nz (float) and face vertex_indices (uchar count, int indices),
// the layout bop_toolkit reads.
void write_ply(const std::filesystem::path& path, const Mesh& mesh,
               PlyEncoding encoding = PlyEncoding::binary_little_endian);

// Binary STL (triangle soup with facet normals; STL has no units).
void write_stl(const std::filesystem::path& path, const Mesh& mesh);

// Wavefront OBJ with vertex normals.
void write_obj(const std::filesystem::path& path, const Mesh& mesh);

// glTF 2.0: .gltf with the buffer embedded as base64 (binary = false) or .glb (binary = true).
void write_gltf(const std::filesystem::path& path, const Mesh& mesh, bool binary);

void write_mesh(const std::filesystem::path& path, const Mesh& mesh, MeshFormat format);

// "ply", "ply-ascii", "stl", "obj", "gltf", "glb"; throws binpick::InputError otherwise.
MeshFormat mesh_format_named(const std::string& name);

// The file extension of a format, with the dot (".ply" for both PLY encodings).
std::string extension_of(MeshFormat format);

}  // namespace binpick
