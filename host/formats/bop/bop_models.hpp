// The models part of a BOP dataset (bop.felk.cvut.cz): models/obj_NNNNNN.ply in mm with normals,
// and models/models_info.json with the diameter, bounding box and known symmetries.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "host/core/mesh.hpp"
#include "host/core/symmetry.hpp"

namespace binpick {

// The models_info.json entry of one object: diameter, min_x/y/z, size_x/y/z, and
// symmetries_continuous / symmetries_discrete when there are any.
nlohmann::json bop_model_info(const Mesh& mesh, const PartSymmetries& symmetries);

// Writes dataset/models/obj_<obj_id, 6 digits>.ply and adds (or replaces) the object's entry in
// dataset/models/models_info.json, keeping the other objects' entries. Creates the directories.
void write_bop_models(const std::filesystem::path& dataset, const Mesh& mesh, int obj_id = 1,
                      const PartSymmetries& symmetries = {});

}  // namespace binpick
