// The models part of a BOP dataset (bop.felk.cvut.cz): models/obj_NNNNNN.ply in mm with normals,
// and models/models_info.json with the diameter, bounding box and known symmetries.
#pragma once

#include <filesystem>
#include <string>
#include <nlohmann/json.hpp>

#include "host/core/mesh.hpp"
#include "host/core/symmetry.hpp"

namespace binpick {

// The models_info.json entry of one object: diameter, min_x/y/z, size_x/y/z, and
// symmetries_continuous / symmetries_discrete when there are any.
nlohmann::json bop_model_info(const Mesh& mesh, const PartSymmetries& symmetries);

// Writes dataset/FOLDER/obj_<obj_id, 6 digits>.ply and adds (or replaces) the object's entry in
// dataset/FOLDER/models_info.json, keeping the other objects' entries. Creates the directories.
// FOLDER: models, or models_eval for the models the toolkit evaluates with.
void write_bop_models(const std::filesystem::path& dataset, const Mesh& mesh, int obj_id = 1,
                      const PartSymmetries& symmetries = {}, const std::string& folder = "models");

// BOP's models_eval/ entry of a model: the mesh with no edge longer than this share of its
// diameter (split_long_edges), written with write_bop_models.
inline constexpr double kEvalModelEdgeShare = 0.025;
void write_bop_eval_model(const std::filesystem::path& dataset, const Mesh& mesh, int obj_id,
                          const PartSymmetries& symmetries);

}  // namespace binpick
