// The model vertices BOP's pose errors are measured on: the toolkit evaluates against
// models_eval/obj_NNNNNN.ply (evenly resampled surfaces); a dataset without models_eval/ is
// measured on models/obj_NNNNNN.ply.
#pragma once

#include <filesystem>
#include <map>
#include <set>
#include <vector>

#include <Eigen/Core>

namespace binpick::eval {

struct EvalVertices {
  std::map<int, std::vector<Eigen::Vector3d>> by_object;  // mm, model frame
  std::filesystem::path directory;                       // models_eval/ or models/
};

// directory/obj_NNNNNN.ply, BOP's name of an object's model file.
std::filesystem::path bop_model_path(const std::filesystem::path& directory, int obj_id);

// The directory BOP's errors are measured in: root/models_eval/ if it has obj_NNNNNN.ply for the
// first of obj_ids, else root/models/.
std::filesystem::path eval_vertices_directory(const std::filesystem::path& root,
                                              const std::set<int>& obj_ids);

// The file of the first obj_id that directory lacks; empty if it has them all.
std::filesystem::path first_missing_model(const std::filesystem::path& directory,
                                          const std::set<int>& obj_ids);

// The vertices of each obj_id from eval_vertices_directory(). Throws InputError naming the file
// if one is missing, is not a PLY, or has no vertex.
EvalVertices load_eval_vertices(const std::filesystem::path& root, const std::set<int>& obj_ids);

}  // namespace binpick::eval
