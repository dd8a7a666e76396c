#include "host/eval/metrics/eval_vertices.hpp"

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/formats/mesh/mesh_readers.hpp"

namespace binpick::eval {
namespace {

namespace fs = std::filesystem;

std::vector<Eigen::Vector3d> read_vertices(const fs::path& path) {
  if (!fs::exists(path)) throw InputError("model " + path.string() + " does not exist");
  Mesh mesh;
  try {
    mesh = read_ply(read_file_bytes(path));
  } catch (const InputError& e) {
    throw InputError(path.string() + ": " + e.what());
  }
  if (mesh.positions.empty()) throw InputError(path.string() + " has no vertex");
  std::vector<Eigen::Vector3d> vertices;
  vertices.reserve(mesh.positions.size());
  for (const auto& p : mesh.positions) vertices.push_back(p.cast<double>());
  return vertices;
}

}  // namespace

fs::path bop_model_path(const fs::path& dir, int obj_id) {
  return dir / fmt::format("obj_{:06d}.ply", obj_id);
}

fs::path eval_vertices_directory(const fs::path& root, const std::set<int>& obj_ids) {
  const fs::path eval_dir = root / "models_eval";
  const bool use_eval = !obj_ids.empty() && fs::exists(bop_model_path(eval_dir, *obj_ids.begin()));
  return use_eval ? eval_dir : root / "models";
}

fs::path first_missing_model(const fs::path& directory, const std::set<int>& obj_ids) {
  for (int id : obj_ids)
    if (!fs::exists(bop_model_path(directory, id))) return bop_model_path(directory, id);
  return {};
}

EvalVertices load_eval_vertices(const fs::path& root, const std::set<int>& obj_ids) {
  EvalVertices out;
  out.directory = eval_vertices_directory(root, obj_ids);
  for (int id : obj_ids) out.by_object[id] = read_vertices(bop_model_path(out.directory, id));
  return out;
}

}  // namespace binpick::eval
