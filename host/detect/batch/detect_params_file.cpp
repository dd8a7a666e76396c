#include "host/detect/batch/detect_params_file.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"

namespace binpick {
namespace {

using Json = nlohmann::json;

// One accessor pair per parameter: the table the file reader and writer share.
struct Field {
  std::function<void(DetectParams&, const Json&, const std::string& where)> set;
  std::function<Json(const DetectParams&)> get;
};

Field real(double DetectParams::*m) {
  return {[m](DetectParams& p, const Json& v, const std::string& where) {
            if (!v.is_number()) throw InputError(where + " must be a number");
            p.*m = v.get<double>();
          },
          [m](const DetectParams& p) { return Json(p.*m); }};
}

Field count(std::uint32_t DetectParams::*m) {
  return {[m](DetectParams& p, const Json& v, const std::string& where) {
            if (!v.is_number_integer() || v.get<std::int64_t>() < 0 ||
                v.get<std::int64_t>() > 1000000)
              throw InputError(where + " must be a non-negative integer");
            p.*m = static_cast<std::uint32_t>(v.get<std::int64_t>());
          },
          [m](const DetectParams& p) { return Json(p.*m); }};
}

Field text(std::string DetectParams::*m) {
  return {[m](DetectParams& p, const Json& v, const std::string& where) {
            if (!v.is_string()) throw InputError(where + " must be a string");
            p.*m = v.get<std::string>();
          },
          [m](const DetectParams& p) { return Json(p.*m); }};
}

const std::map<std::string, Field>& fields() {
  static const std::map<std::string, Field> table = {
      {"ref-ratio", real(&DetectParams::ref_ratio)},
      {"hypotheses", count(&DetectParams::hypotheses)},
      {"more-hypotheses", count(&DetectParams::more_hypotheses)},
      {"highest-up", count(&DetectParams::highest_up)},
      {"through-walls", count(&DetectParams::through_walls)},
      {"over-rim", count(&DetectParams::over_rim)},
      {"flat-region", real(&DetectParams::flat_region)},
      {"confident", real(&DetectParams::confident)},
      {"exclusion-ratio", real(&DetectParams::exclusion_ratio)},
      {"crop-ratio", real(&DetectParams::crop_ratio)},
      {"cluster-distance", real(&DetectParams::cluster_distance)},
      {"cluster-angle", real(&DetectParams::cluster_angle)},
      {"peaks-per-ref", count(&DetectParams::peaks_per_ref)},
      {"peak-ratio", real(&DetectParams::peak_ratio)},
      {"normal-ratio", real(&DetectParams::normal_ratio)},
      {"unique-votes", count(&DetectParams::unique_votes)},
      {"spread-votes", count(&DetectParams::spread_votes)},
      {"local-peaks", count(&DetectParams::local_peaks)},
      {"bucket-cap", real(&DetectParams::bucket_cap)},
      {"noise-voxel", real(&DetectParams::noise_voxel)},
      {"candidates", count(&DetectParams::candidates)},
      {"plane-search", real(&DetectParams::plane_search)},
      {"refine-iterations", count(&DetectParams::refine_iterations)},
      {"verify-tolerance", real(&DetectParams::verify_tolerance)},
      {"verify-noise-factor", real(&DetectParams::verify_noise_factor)},
      {"verify-patch", real(&DetectParams::verify_patch)},
      {"verify-ray", real(&DetectParams::verify_ray)},
      {"verify-twin", real(&DetectParams::verify_twin)},
      {"verify-edge", real(&DetectParams::verify_edge)},
      {"verify-lookalike", real(&DetectParams::verify_lookalike)},
      {"verify-area", real(&DetectParams::verify_area)},
      {"verify-rival", real(&DetectParams::verify_rival)},
      {"verify-through", real(&DetectParams::verify_through)},
      {"roi", text(&DetectParams::roi)},
      {"bin", text(&DetectParams::bin)},
      {"bin-margin", real(&DetectParams::bin_margin)},
      {"instances", count(&DetectParams::instances)},
  };
  return table;
}

}  // namespace

const std::set<std::string>& detect_param_names() {
  static const std::set<std::string> names = [] {
    std::set<std::string> n;
    for (const auto& [name, field] : fields()) n.insert(name);
    return n;
  }();
  return names;
}

void apply_params_file(const std::filesystem::path& path, DetectParams& params,
                       const std::set<std::string>& keep) {
  apply_params_text(read_file_bytes(path), path.string(), params, keep);
}

void apply_params_text(std::string_view text, const std::string& name, DetectParams& params,
                       const std::set<std::string>& keep) {
  Json json;
  try {
    json = Json::parse(text);
  } catch (const Json::exception& e) {
    throw InputError("parameter file " + name + " is not valid JSON: " + e.what());
  }
  if (!json.is_object())
    throw InputError("parameter file " + name + " must hold a JSON object");
  for (const auto& [raw_key, value] : json.items()) {
    std::string key = raw_key;
    std::replace(key.begin(), key.end(), '_', '-');
    const auto it = fields().find(key);
    if (it == fields().end()) {
      std::string known;
      for (const auto& name : detect_param_names()) known += (known.empty() ? "" : ", ") + name;
      throw InputError("parameter file " + name + ": unknown parameter '" + raw_key +
                       "' (known: " + known + ")");
    }
    if (keep.count(key)) continue;
    it->second.set(params, value, "parameter file " + name + ": '" + raw_key + "'");
  }
}

std::string params_json(const DetectParams& params) {
  Json json = Json::object();
  for (const auto& [name, field] : fields()) json[name] = field.get(params);
  return json.dump();
}

}  // namespace binpick
