// The one entry point for part models: a file (.gltf .glb .ply .stl .obj) or builtin:NAME,
// scaled to millimetres and checked, with normals.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "host/core/mesh.hpp"
#include "host/core/symmetry.hpp"

namespace binpick {

struct ModelOptions {
  double unit_scale = 1.0;         // file units to mm (STL has no units; 1000 for metres)
  std::optional<double> diameter;  // if set, rescale about the origin to this exact diameter
  std::string mesh_name;           // glTF: one node or mesh of an assembly
};

struct Model {
  Mesh mesh;
  PartSymmetries symmetries;  // known only for built-in parts; scaled like the mesh
};

// Loads spec (a file path or "builtin:NAME"). The result has triangles, unit per-vertex normals
// (from the file, or computed with sharp edges kept), no unused vertices, and positions
// multiplied by unit_scale and then rescaled to the requested diameter. Throws
// binpick::InputError naming spec for anything wrong with the file or the options.
Model load_model_with_symmetries(const std::string& spec, const ModelOptions& options);

// load_model_with_symmetries(spec, options).mesh
Mesh load_model(const std::string& spec, const ModelOptions& options);

// The same for a model file held in memory: format is its extension without the dot ("ply",
// "stl", "obj", "gltf", "glb"); files it refers to (glTF buffers, OBJ materials) are looked up
// in directory. Error messages do not name a file.
Mesh parse_model(std::string_view bytes, std::string_view format, const ModelOptions& options,
                 const std::filesystem::path& directory = {});

}  // namespace binpick
