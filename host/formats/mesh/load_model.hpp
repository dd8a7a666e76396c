// The one entry point for part model files (.gltf .glb .ply .stl .obj), scaled to millimetres
// and checked, with normals. (`builtin:NAME` is resolved above this layer, by the app's model
// options, which hand the built-in mesh to complete_model.)
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

// Loads the model file at path. The result has triangles, unit per-vertex normals (from the
// file, or computed with sharp edges kept), no unused vertices, and positions multiplied by
// unit_scale and then rescaled to the requested diameter. Throws binpick::InputError naming
// path for anything wrong with the file or the options.
Model load_model_with_symmetries(const std::string& path, const ModelOptions& options);

// load_model_with_symmetries(path, options).mesh
Mesh load_model(const std::string& path, const ModelOptions& options);

// Why a mesh in mm is probably in the wrong unit, or "" when its size is plausible for a part
// picked from a bin (its largest bounding-box side from kMinPlausibleMm to kMaxPlausibleMm).
// A file in metres (glTF's unit by its specification, and many STL exports) read as mm makes
// a part a thousand times too small, whose model then matches nothing, with no error: the
// loaders log this as a warning (also for a bin mesh, which synth reads the same way).
inline constexpr double kMinPlausibleMm = 1.0, kMaxPlausibleMm = 5000.0;
std::string implausible_size(const Mesh& mesh);

// The same checks, repairs and scaling for a mesh from elsewhere (a built-in part): name is
// what error messages start with.
Model complete_model(Mesh mesh, PartSymmetries symmetries, const std::string& name,
                     const ModelOptions& options);

// The same for a model file held in memory: format is its extension without the dot ("ply",
// "stl", "obj", "gltf", "glb"); files it refers to (glTF buffers, OBJ materials) are looked up
// in directory. Error messages do not name a file.
Mesh parse_model(std::string_view bytes, std::string_view format, const ModelOptions& options,
                 const std::filesystem::path& directory = {});

}  // namespace binpick
