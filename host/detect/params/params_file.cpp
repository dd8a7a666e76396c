#include "host/detect/params/params_file.hpp"

#include <algorithm>
#include <map>

#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/detect/params/param_table.hpp"

namespace binpick {
namespace {

using Json = nlohmann::json;

void set_from_json(const ParamInfo& info, DetectParams& p, const Json& v,
                   const std::string& where) {
  std::visit(
      [&](auto member) {
        using T = std::remove_cvref_t<decltype(p.*member)>;
        if constexpr (std::is_same_v<T, double>) {
          if (!v.is_number()) throw InputError(where + " must be a number");
          p.*member = v.get<double>();
        } else if constexpr (std::is_same_v<T, std::uint32_t>) {
          if (!v.is_number_integer() || v.get<std::int64_t>() < 0 ||
              v.get<std::int64_t>() > 1000000)
            throw InputError(where + " must be a non-negative integer");
          p.*member = static_cast<std::uint32_t>(v.get<std::int64_t>());
        } else if constexpr (std::is_same_v<T, bool>) {
          // Files from before the on/off parameters were flags hold 0 or 1.
          if (v.is_boolean()) p.*member = v.get<bool>();
          else if (v.is_number_integer() && (v.get<std::int64_t>() == 0 || v.get<std::int64_t>() == 1))
            p.*member = v.get<std::int64_t>() == 1;
          else throw InputError(where + " must be true or false (or 1 or 0)");
        } else {
          if (!v.is_string()) throw InputError(where + " must be a string");
          p.*member = v.get<std::string>();
        }
      },
      info.member);
}

Json to_json(const ParamInfo& info, const DetectParams& p) {
  return std::visit([&](auto member) { return Json(p.*member); }, info.member);
}

}  // namespace

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
  if (!json.is_object()) throw InputError("parameter file " + name + " must hold a JSON object");
  for (const auto& [raw_key, value] : json.items()) {
    std::string key = raw_key;
    std::replace(key.begin(), key.end(), '_', '-');
    const ParamInfo* info = find_param(key);
    if (!info) {
      std::string known;
      for (const ParamInfo& p : detect_param_table())
        known += (known.empty() ? "" : ", ") + std::string(p.name);
      throw InputError("parameter file " + name + ": unknown parameter '" + raw_key +
                       "' (known: " + known + ")");
    }
    if (keep.count(info->name)) continue;
    set_from_json(*info, params, value, "parameter file " + name + ": '" + raw_key + "'");
  }
}

std::string params_json(const DetectParams& params) {
  Json json = Json::object();  // nlohmann's objects keep their keys sorted
  for (const ParamInfo& p : detect_param_table()) json[p.name] = to_json(p, params);
  return json.dump();
}

}  // namespace binpick
