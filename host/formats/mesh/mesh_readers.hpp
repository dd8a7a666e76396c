// One reader per model file format. Each returns the mesh as stored (file units; normals only
// if the file has them, possibly not unit length; faces fan-triangulated) and throws
// binpick::InputError with a message that does not name the file: load_model() adds the name
// and does the checks common to all formats.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "host/core/mesh.hpp"

namespace binpick {

// PLY: ascii, binary_little_endian or binary_big_endian; any scalar types.
Mesh read_ply(std::string_view bytes);

// STL: binary or ascii (told apart by the binary size rule, not by the "solid" prefix).
Mesh read_stl(std::string_view bytes);
// The triangle count of a binary STL, when the bytes are one by the size rule (84 header bytes and
// 50 a triangle, exactly as many as the header says); none otherwise.
std::optional<std::uint32_t> binary_stl_triangles(std::string_view bytes);

// Wavefront OBJ via tinyobjloader (materials are ignored; mtllib files are looked up in
// directory).
Mesh read_obj(std::string_view bytes, const std::filesystem::path& directory);

// glTF 2.0 (.gltf text with embedded or external buffers, or .glb binary, told apart by the
// GLB magic) via tinygltf; external buffers are looked up in directory. Every triangle
// primitive of the default scene placed by its node's world transform, or, if mesh_name is not
// empty, only the node of that name (with its children) or else the mesh of that name.
Mesh read_gltf(std::string_view bytes, const std::filesystem::path& directory,
               const std::string& mesh_name);

}  // namespace binpick
