#include "host/formats/mesh/load_model.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <new>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/core/diameter.hpp"
#include "host/core/mesh_geometry.hpp"
#include "host/core/mesh_normals.hpp"
#include "host/core/mesh_orientation.hpp"
#include "host/formats/mesh/announced_triangles.hpp"
#include "host/formats/mesh/mesh_readers.hpp"
#include "host/core/mesh_topology.hpp"

namespace binpick {
namespace {

void check_options(const std::string& spec, const ModelOptions& options) {
  if (!(std::isfinite(options.unit_scale) && options.unit_scale > 0))
    throw InputError(spec + ": unit scale must be a positive number, not " +
                     std::to_string(options.unit_scale));
  if (options.diameter && !(std::isfinite(*options.diameter) && *options.diameter > 0))
    throw InputError(spec + ": diameter must be a positive number of mm, not " +
                     std::to_string(*options.diameter));
}

std::string lowercase(std::string_view text) {
  std::string result(text);
  std::transform(result.begin(), result.end(), result.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return result;
}

Mesh read_model(std::string_view bytes, std::string_view format, const ModelOptions& options,
                const std::filesystem::path& directory) {
  const std::string kind = lowercase(format);
  const bool gltf = kind == "gltf" || kind == "glb";
  if (!options.mesh_name.empty() && !gltf)
    throw InputError("--mesh selects a node of a glTF file; this is a ." + kind + " file");
  if (const auto triangles = announced_triangles(bytes, kind); triangles > kMaxModelTriangles)
    throw InputError(fmt::format(
        "the model has {} triangles, more than binpick reads ({}): decimate it first (training "
        "samples a few thousand points of its surface, so little detail is lost)",
        triangles, kMaxModelTriangles));
  if (kind == "ply") return read_ply(bytes);
  if (kind == "stl") return read_stl(bytes);
  if (kind == "obj") return read_obj(bytes, directory);
  if (gltf) return read_gltf(bytes, directory, options.mesh_name);
  throw InputError("unsupported model format '." + kind +
                   "' (expected .gltf .glb .ply .stl .obj, or builtin:NAME)");
}

// What orient_outward changed, said once: a silent repair would hide a broken export.
void report_orientation(const OrientationReport& r) {
  if (r.made_consistent > 0)
    spdlog::warn("{} triangles were wound against their neighbours; turned them", r.made_consistent);
  if (r.turned_out > 0)
    spdlog::warn("the model was inside out ({} triangles wound clockwise seen from outside); "
                 "turned them", r.turned_out);
  if (r.normals_flipped) spdlog::warn("the file's normals pointed inwards; negated them");
  if (r.undecided > 0)
    spdlog::warn("{} triangles belong to open surfaces without normals: which side is outside "
                 "cannot be told, they are used as wound (counter-clockwise = outside)",
                 r.undecided);
}

// The checks and repairs every format needs, in file units.
void check_and_complete(Mesh& mesh) {
  for (const auto& t : mesh.triangles) {
    for (auto v : t) {
      if (v >= mesh.positions.size())
        throw InputError("face refers to vertex " + std::to_string(v) + " but there are only " +
                         std::to_string(mesh.positions.size()) + " vertices");
    }
  }
  remove_collapsed_triangles(mesh);
  if (mesh.triangles.empty()) throw InputError("the model has no triangles");
  remove_unreferenced_vertices(mesh);
  for (const auto& p : mesh.positions) {
    if (!p.allFinite())
      throw InputError("the model has a vertex with a NaN or infinite coordinate");
  }
  if (!mesh.normals.empty() && !normalize_normals(mesh)) {
    spdlog::warn("some normals in the file are zero or not finite; computing normals instead");
    mesh.normals.clear();
  }
  report_orientation(orient_outward(mesh));
  if (mesh.normals.empty()) {
    merge_duplicate_vertices(mesh);
    remove_collapsed_triangles(mesh);
    if (mesh.triangles.empty())
      throw InputError("the model has no triangles with distinct corners");
    compute_crease_normals(mesh);
  }
}

// Applies the unit scale, then the diameter; returns the total factor applied.
double scale_to_millimetres(Mesh& mesh, const ModelOptions& options) {
  double factor = options.unit_scale;
  if (options.diameter) {
    // Scaling is uniform about the origin, so the unit scale cancels out.
    const double file_diameter = exact_diameter(mesh.positions);
    if (!(file_diameter > 0)) throw InputError("all vertices coincide; the model has no size");
    factor = *options.diameter / file_diameter;
  }
  if (factor != 1.0) scale_mesh(mesh, factor);
  for (const auto& p : mesh.positions) {
    if (!p.allFinite()) throw InputError("scaled coordinates overflow; check --unit-scale");
  }
  return factor;
}

void warn_if_implausible(const std::string& name, const Mesh& mesh) {
  if (const std::string why = implausible_size(mesh); !why.empty())
    spdlog::warn("{}: {}", name, why);
}

// Runs make (which returns the mesh as read) and completes it; every error names `name`.
template <class Make>
Model named_model(const std::string& name, const ModelOptions& options, Make&& make) {
  check_options(name, options);
  try {
    Model model = make();
    check_and_complete(model.mesh);
    model.symmetries = model.symmetries.scaled(scale_to_millimetres(model.mesh, options));
    warn_if_implausible(name, model.mesh);
    return model;
  } catch (const InputError& e) {
    const std::string message = e.what();
    // Messages from read_file_bytes already start with the path.
    if (message.starts_with(name)) throw;
    throw InputError(name + ": " + message);
  } catch (const std::bad_alloc&) {
    throw InputError(name + ": out of memory while reading (is the file corrupt?)");
  }
}

}  // namespace

std::string implausible_size(const Mesh& mesh) {
  if (mesh.positions.empty()) return "";
  const double extent = double(bounding_box(mesh.positions).size().maxCoeff());
  if (extent < kMinPlausibleMm)
    return fmt::format("the mesh is only {:.3g} mm across: if the file is in metres (glTF always "
                       "is), a part needs --unit-scale 1000 or --diameter with its size in mm "
                       "(a --bin-mesh file: scale it to mm)",
                       extent);
  if (extent > kMaxPlausibleMm)
    return fmt::format("the mesh is {:.4g} mm across: if the file is in micrometres, a part "
                       "needs --unit-scale 0.001 or --diameter with its size in mm (a --bin-mesh "
                       "file: scale it to mm)",
                       extent);
  return "";
}

Model load_model_with_symmetries(const std::string& path, const ModelOptions& options) {
  return named_model(path, options, [&] {
    const std::filesystem::path file = path;
    const std::string bytes = read_file_bytes(file);
    const std::string extension = file.extension().string();  // with its dot, or empty
    return Model{read_model(bytes, std::string_view(extension).substr(extension.empty() ? 0 : 1),
                            options, file.parent_path()),
                 {}};
  });
}

Mesh load_model(const std::string& path, const ModelOptions& options) {
  return load_model_with_symmetries(path, options).mesh;
}

Model complete_model(Mesh mesh, PartSymmetries symmetries, const std::string& name,
                     const ModelOptions& options) {
  return named_model(name, options,
                     [&] { return Model{std::move(mesh), std::move(symmetries)}; });
}

Mesh parse_model(std::string_view bytes, std::string_view format, const ModelOptions& options,
                 const std::filesystem::path& directory) {
  check_options("model", options);
  try {
    Mesh mesh = read_model(bytes, format, options, directory);
    check_and_complete(mesh);
    scale_to_millimetres(mesh, options);
    warn_if_implausible("model", mesh);
    return mesh;
  } catch (const std::bad_alloc&) {
    throw InputError("out of memory while reading the model (is it corrupt?)");
  }
}

}  // namespace binpick
