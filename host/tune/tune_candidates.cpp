#include "host/tune/tune_candidates.hpp"

#include <ostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/atomic_file.hpp"
#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/train/model_store.hpp"

namespace binpick {
namespace fs = std::filesystem;
using Json = nlohmann::json;

fs::path write_candidates(const fs::path& dir, const std::vector<TunePoint>& points) {
  Json list = Json::array();
  for (const TunePoint& p : points) {
    Json item = Json::object();
    for (const TuneAxis& axis : tune_axes()) item[axis.name] = axis.get(p);
    item["key"] = checksum_hex(point_key(p));
    list.push_back(item);
  }
  const std::string text = Json{{"points", list}}.dump(1) + "\n";
  const fs::path file = dir / ("points-" + checksum_hex(text).substr(0, 16) + ".json");
  write_file_atomically(file, [&](std::ostream& s) { s << text; });
  return file;
}

std::vector<TunePoint> read_candidates(const fs::path& file, const TunePoint& start) {
  if (!fs::is_regular_file(file))
    throw InputError(fmt::format("--points {}: no such file", file.string()));
  const auto bad = [&](const std::string& why) {
    return InputError(fmt::format("--points {}: {}", file.string(), why));
  };
  Json doc;
  try {
    doc = Json::parse(read_file_bytes(file));
  } catch (const Json::exception& e) {
    throw bad(std::string("not JSON: ") + e.what());
  }
  if (!doc.is_object() || !doc.contains("points") || !doc["points"].is_array())
    throw bad("expected {\"points\": [...]}");
  std::vector<TunePoint> points;
  for (const Json& item : doc["points"]) {
    TunePoint p = start;
    for (const TuneAxis& axis : tune_axes()) {
      if (!item.is_object() || !item.contains(axis.name) || !item[axis.name].is_number())
        throw bad(fmt::format("point {} has no number '{}'", points.size(), axis.name));
      axis.set(p, item[axis.name].get<double>());
    }
    if (!item.contains("key") || item["key"] != checksum_hex(point_key(p)))
      throw bad(fmt::format(
          "point {} is not the one its key names: the file was made by a tune with other "
          "options than these",
          points.size()));
    points.push_back(p);
  }
  if (points.empty()) throw bad("no points");
  return points;
}

}  // namespace binpick
