#include "host/formats/grasps/grasp_json.hpp"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"

namespace binpick {
namespace {

using nlohmann::json;

double number(const json& j, const char* key, const std::string& what) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number())
    throw InputError(fmt::format("{}: \"{}\" (a number) expected", what, key));
  const double v = j[key].get<double>();
  if (!std::isfinite(v)) throw InputError(fmt::format("{}: \"{}\" is not finite", what, key));
  return v;
}

double positive(const json& j, const char* key, const std::string& what) {
  const double v = number(j, key, what);
  if (!(v > 0 && v < 1e6)) throw InputError(fmt::format("{}: \"{}\" must be positive", what, key));
  return v;
}

Eigen::Vector3d vector3(const json& j, const char* key, const std::string& what) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_array() || j[key].size() != 3)
    throw InputError(fmt::format("{}: \"{}\" (3 numbers) expected", what, key));
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) {
    if (!j[key][k].is_number()) throw InputError(fmt::format("{}: \"{}\" (3 numbers) expected", what, key));
    v[k] = j[key][k].get<double>();
  }
  if (!v.allFinite()) throw InputError(fmt::format("{}: \"{}\" is not finite", what, key));
  return v;
}

Eigen::Vector3d direction(const json& j, const char* key, const std::string& what) {
  const Eigen::Vector3d v = vector3(j, key, what);
  if (!(v.norm() > 1e-9)) throw InputError(fmt::format("{}: \"{}\" is zero", what, key));
  return v.normalized();
}

json array_of(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

}  // namespace

std::vector<Grasp> parse_grasps_json(std::string_view text, const std::string& name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(fmt::format("{}: not JSON ({})", name, e.what()));
  }
  if (!j.is_object()) throw InputError(name + ": a JSON object of \"suction\" and \"parallel\" grasps expected");
  for (const auto& [key, value] : j.items())
    if (key != "suction" && key != "parallel")
      throw InputError(fmt::format("{}: unknown key \"{}\" (\"suction\", \"parallel\")", name, key));
  std::vector<Grasp> grasps;
  const auto list = [&](const char* key) {
    if (!j.contains(key)) return json::array();
    if (!j[key].is_array()) throw InputError(fmt::format("{}: \"{}\" must be a list", name, key));
    return j[key];
  };
  const json suction = list("suction"), parallel = list("parallel");
  for (std::size_t i = 0; i < suction.size(); ++i) {
    const std::string what = fmt::format("{}: suction grasp {}", name, i);
    Grasp g;
    g.kind = Grasp::Kind::suction;
    g.point = vector3(suction[i], "point", what);
    g.approach = direction(suction[i], "approach", what);
    g.closing = across(g.approach);
    g.size = positive(suction[i], "cup_diameter", what);
    grasps.push_back(g);
  }
  for (std::size_t i = 0; i < parallel.size(); ++i) {
    const std::string what = fmt::format("{}: parallel grasp {}", name, i);
    Grasp g;
    g.kind = Grasp::Kind::parallel;
    g.point = vector3(parallel[i], "centre", what);
    g.approach = direction(parallel[i], "approach", what);
    const Eigen::Vector3d c = direction(parallel[i], "closing", what);
    const Eigen::Vector3d perpendicular = c - g.approach * g.approach.dot(c);
    if (!(perpendicular.norm() > 0.5))  // within 60 degrees of perpendicular
      throw InputError(what + ": \"closing\" must be across \"approach\"");
    g.closing = perpendicular.normalized();
    g.size = positive(parallel[i], "width", what);
    grasps.push_back(g);
  }
  if (grasps.empty()) throw InputError(name + ": no grasp");
  return grasps;
}

std::vector<Grasp> read_grasps_json(const std::filesystem::path& path) {
  return parse_grasps_json(read_file_bytes(path), path.string());
}

std::string grasps_json(const std::vector<Grasp>& grasps) {
  json suction = json::array(), parallel = json::array();
  for (const Grasp& g : grasps) {
    if (g.kind == Grasp::Kind::suction)
      suction.push_back({{"point", array_of(g.point)}, {"approach", array_of(g.approach)},
                         {"cup_diameter", g.size}});
    else
      parallel.push_back({{"centre", array_of(g.point)}, {"approach", array_of(g.approach)},
                          {"closing", array_of(g.closing)}, {"width", g.size}});
  }
  return json{{"suction", suction}, {"parallel", parallel}}.dump(1) + "\n";
}

Gripper parse_gripper(const std::string& spec) {
  const std::string what = "--gripper " + spec;
  for (const char* kind : {"suction:", "parallel:"}) {
    if (spec.rfind(kind, 0) != 0) continue;
    std::vector<double> v;
    std::string rest = spec.substr(std::string(kind).size());
    std::size_t at = 0;
    while (at <= rest.size()) {
      const std::size_t comma = std::min(rest.find(',', at), rest.size());
      const std::string field = rest.substr(at, comma - at);
      char* end = nullptr;
      const double x = std::strtod(field.c_str(), &end);
      if (field.empty() || *end != '\0' || !(std::isfinite(x) && x > 0 && x < 1e6))
        throw InputError(what + ": four positive sizes in mm expected, separated by commas");
      v.push_back(x);
      at = comma + 1;
    }
    if (v.size() != 4) throw InputError(what + ": four positive sizes in mm expected, separated by commas");
    return kind[0] == 's' ? Gripper::suction(v[0], v[1], v[2], v[3])
                          : Gripper::parallel(v[0], v[1], v[2], v[3]);
  }
  return parse_gripper_json(read_file_bytes(spec), spec);
}

Gripper parse_gripper_json(std::string_view text, const std::string& name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(fmt::format("{}: not JSON ({})", name, e.what()));
  }
  if (j.is_object() && j.size() == 1 && j.contains("suction"))
    return Gripper::suction(positive(j["suction"], "cup_diameter", name),
                            positive(j["suction"], "standoff", name),
                            positive(j["suction"], "body_diameter", name),
                            positive(j["suction"], "body_length", name));
  if (j.is_object() && j.size() == 1 && j.contains("parallel"))
    return Gripper::parallel(positive(j["parallel"], "finger_width", name),
                             positive(j["parallel"], "finger_depth", name),
                             positive(j["parallel"], "finger_length", name),
                             positive(j["parallel"], "palm_height", name));
  throw InputError(name + ": a JSON object with one key, \"suction\" or \"parallel\", expected");
}

}  // namespace binpick
