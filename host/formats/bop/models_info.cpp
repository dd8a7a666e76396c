#include "host/formats/bop/models_info.hpp"

#include <cmath>
#include <utility>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"

namespace binpick::bop {
namespace {

using nlohmann::json;

// Numbers of a JSON array of exactly n finite numbers; what() names `what` otherwise.
std::vector<double> numbers(const json& value, std::size_t n, const std::string& what) {
  if (!value.is_array() || value.size() != n)
    throw InputError(fmt::format("{} must be an array of {} numbers", what, n));
  std::vector<double> out;
  for (const auto& v : value) {
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      throw InputError(fmt::format("{} must hold {} finite numbers", what, n));
    out.push_back(v.get<double>());
  }
  return out;
}

Eigen::Vector3d vector3(const json& value, const std::string& what) {
  const auto v = numbers(value, 3, what);
  return {v[0], v[1], v[2]};
}

ContinuousSymmetry continuous(const json& entry, const std::string& where) {
  if (!entry.is_object() || !entry.contains("axis"))
    throw InputError(where + " must be an object with an \"axis\"");
  ContinuousSymmetry s;
  s.axis = vector3(entry["axis"], where + " axis");
  if (s.axis.norm() < 1e-9) throw InputError(where + " axis has zero length");
  s.axis.normalize();
  s.offset = entry.contains("offset") ? vector3(entry["offset"], where + " offset")
                                      : Eigen::Vector3d::Zero();
  return s;
}

Eigen::Matrix4d discrete(const json& entry, const std::string& where) {
  const auto v = numbers(entry, 16, where);
  Eigen::Matrix4d m;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = v[i];
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  // Files round their values (bop_models writes 1e-16 as 0): accept what is a rotation to 1e-4.
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-4 || R.determinant() < 0)
    throw InputError(where + " is not a rigid transform (its 3x3 part is not a rotation)");
  return m;
}

// The centre of the bounding box min_x .. size_z if all six are finite numbers, else the origin
// (the box is informative only: evaluation uses it to place a pose on a part).
Eigen::Vector3d box_centre(const json& entry) {
  Eigen::Vector3d lo, size;
  for (int a = 0; a < 3; ++a) {
    for (auto [key, out] : {std::pair{"min_", &lo}, std::pair{"size_", &size}}) {
      const std::string name = std::string(key) + "xyz"[a];
      if (!entry.contains(name) || !entry[name].is_number() ||
          !std::isfinite(entry[name].get<double>()))
        return Eigen::Vector3d::Zero();
      (*out)[a] = entry[name].get<double>();
    }
  }
  return lo + size / 2;
}

ModelInfo model_info(const json& entry, const std::string& where) {
  if (!entry.is_object()) throw InputError(where + " must be a JSON object");
  ModelInfo info;
  if (!entry.contains("diameter") || !entry["diameter"].is_number())
    throw InputError(where + " has no numeric \"diameter\"");
  info.diameter = entry["diameter"].get<double>();
  if (!(info.diameter > 0 && std::isfinite(info.diameter)))
    throw InputError(fmt::format("{} diameter {} must be positive", where, info.diameter));
  info.centre = box_centre(entry);
  if (entry.contains("symmetries_continuous")) {
    const auto& list = entry["symmetries_continuous"];
    if (!list.is_array()) throw InputError(where + " symmetries_continuous must be an array");
    for (std::size_t i = 0; i < list.size(); ++i)
      info.symmetries.continuous.push_back(
          continuous(list[i], fmt::format("{} symmetries_continuous[{}]", where, i)));
  }
  if (entry.contains("symmetries_discrete")) {
    const auto& list = entry["symmetries_discrete"];
    if (!list.is_array()) throw InputError(where + " symmetries_discrete must be an array");
    for (std::size_t i = 0; i < list.size(); ++i)
      info.symmetries.discrete.push_back(
          discrete(list[i], fmt::format("{} symmetries_discrete[{}]", where, i)));
  }
  return info;
}

}  // namespace

ModelsInfo parse_models_info(const std::string& text, const std::string& name) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(name + " is not valid JSON: " + e.what());
  }
  if (!root.is_object()) throw InputError(name + " must be a JSON object keyed by object id");
  ModelsInfo out;
  for (auto it = root.begin(); it != root.end(); ++it) {
    int id = 0;
    std::size_t used = 0;
    try {
      id = std::stoi(it.key(), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != it.key().size() || id < 1)
      throw InputError(name + ": key \"" + it.key() + "\" is not an object id (a positive integer)");
    out[id] = model_info(it.value(), name + " object " + it.key());
  }
  if (out.empty()) throw InputError(name + " lists no object");
  return out;
}

ModelsInfo read_models_info(const std::filesystem::path& path) {
  return parse_models_info(read_file_bytes(path), path.string());
}

}  // namespace binpick::bop
