// Reader of BOP's models/models_info.json (docs/formats.md): per object id its diameter and
// the symmetries evaluation must treat as equal poses (written by host/formats/bop/bop_models.cpp).
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "host/core/symmetry.hpp"

namespace binpick::bop {

struct ModelInfo {
  double diameter = 0;  // mm
  PartSymmetries symmetries;
  // The centre of the model's bounding box (min_x + size_x / 2, ...) in the model frame, mm;
  // the origin unless the file gives all six numbers.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

// Keyed by obj_id.
using ModelsInfo = std::map<int, ModelInfo>;

// Parses models_info.json text read from `name` (used in messages). Throws InputError naming the
// file and the object for: not a JSON object, a key that is not an object id, a missing or
// non-positive diameter, a continuous symmetry without a 3-vector axis of non-zero length
// (offset defaults to 0), a discrete symmetry that is not 16 numbers (row-major 4x4) whose
// rotation part is a rotation. Other keys are ignored. Axes are normalised.
ModelsInfo parse_models_info(const std::string& text, const std::string& name);

// Reads and parses path.
ModelsInfo read_models_info(const std::filesystem::path& path);

}  // namespace binpick::bop
