#include "host/formats/bop/bop_models.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>

#include "host/core/error.hpp"
#include "host/core/atomic_file.hpp"
#include "host/formats/mesh/mesh_writers.hpp"
#include "host/core/diameter.hpp"
#include "host/core/mesh_refine.hpp"
#include "host/core/mesh_geometry.hpp"

namespace binpick {
namespace {

nlohmann::json symmetries_json(const PartSymmetries& symmetries, nlohmann::json info) {
  if (!symmetries.continuous.empty()) {
    auto& list = info["symmetries_continuous"] = nlohmann::json::array();
    for (const auto& s : symmetries.continuous) {
      list.push_back({{"axis", {s.axis.x(), s.axis.y(), s.axis.z()}},
                      {"offset", {s.offset.x(), s.offset.y(), s.offset.z()}}});
    }
  }
  if (!symmetries.discrete.empty()) {
    auto& list = info["symmetries_discrete"] = nlohmann::json::array();
    for (const auto& m : symmetries.discrete) {
      auto values = nlohmann::json::array();
      for (int row = 0; row < 4; ++row) {
        // Rotations built from sines and cosines carry 1e-16 noise where 0 is meant.
        for (int col = 0; col < 4; ++col)
          values.push_back(std::abs(m(row, col)) < 1e-12 ? 0.0 : m(row, col));
      }
      list.push_back(values);
    }
  }
  return info;
}

nlohmann::json existing_info(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) return nlohmann::json::object();
  std::ifstream in(path);
  nlohmann::json info = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!info.is_object())
    throw InputError(path.string() +
                     " exists but is not a JSON object; remove it or choose another dataset");
  return info;
}

}  // namespace

nlohmann::json bop_model_info(const Mesh& mesh, const PartSymmetries& symmetries) {
  const BoundingBox box = bounding_box(mesh.positions);
  const Eigen::Vector3f size = box.size();
  nlohmann::json info = {{"diameter", exact_diameter(mesh.positions)},
                         {"min_x", box.min.x()},
                         {"min_y", box.min.y()},
                         {"min_z", box.min.z()},
                         {"size_x", size.x()},
                         {"size_y", size.y()},
                         {"size_z", size.z()}};
  return symmetries_json(symmetries, info);
}

void write_bop_models(const std::filesystem::path& dataset, const Mesh& mesh, int obj_id,
                      const PartSymmetries& symmetries, const std::string& folder) {
  if (obj_id < 1 || obj_id > 999999) throw InputError("BOP object ids run from 1 to 999999");
  const auto models = dataset / folder;
  std::error_code ec;
  std::filesystem::create_directories(models, ec);
  if (ec) throw InputError("cannot create " + models.string() + ": " + ec.message());
  char name[32];
  std::snprintf(name, sizeof name, "obj_%06d.ply", obj_id);
  write_ply(models / name, mesh, PlyEncoding::binary_little_endian);

  const auto info_path = models / "models_info.json";
  nlohmann::json info = existing_info(info_path);
  info[std::to_string(obj_id)] = bop_model_info(mesh, symmetries);
  write_file_atomically(info_path, [&](std::ostream& out) { out << info.dump(2) << '\n'; });
}

void write_bop_eval_model(const std::filesystem::path& dataset, const Mesh& mesh, int obj_id,
                          const PartSymmetries& symmetries) {
  const double diameter = exact_diameter(mesh.positions);
  write_bop_models(dataset, split_long_edges(mesh, kEvalModelEdgeShare * diameter), obj_id,
                   symmetries, "models_eval");
}

}  // namespace binpick
