#include "synth/synth_manifest.hpp"
#include "synth/sensor/sensor_options.hpp"

#include <fmt/format.h>

#include "host/core/atomic_file.hpp"
#include "host/core/error.hpp"
#include "host/core/read_file.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Bumped whenever the same options make different bins (drop, decomposition, rendering), so a
// dataset is never resumed or extended with bins of another kind. 2: merged hulls, the
// sliding-window rest test and the final all-dynamic second. 3: the bin has thin walls and a
// rim (and is rendered by default), distractors, intrinsics and tilt.
constexpr int kSynthVersion = 3;

json bin_entry(const SynthOptions& o, const ManifestInputs& in) {
  json bin = {{"render", o.bin_render == BinRender::full ? "full" : "none"}};
  if (o.bin_mesh.empty()) {
    bin["wall_mm"] = o.drop.walls.wall_mm;
    bin["rim_mm"] = o.drop.walls.rim_mm;
  } else {
    bin["mesh"] = o.bin_mesh.string();
    bin["mesh_fnv1a"] = in.bin_mesh_digest;
  }
  return bin;
}

json camera_entry(const SynthOptions& o) {
  json camera = {{"height_mm", o.camera_height_mm}, {"tilt_deg", o.camera_tilt_deg}};
  // Written only when set: datasets made before the roll existed keep their manifest.
  if (o.camera_roll_deg != 0.0) camera["roll_deg"] = o.camera_roll_deg;
  if (o.intrinsics)
    camera["intrinsics"] = *o.intrinsics;
  else
    camera["intrinsics"] = "camera_for_bin";
  return camera;
}

}  // namespace

json synth_manifest(const SynthOptions& o, const ManifestInputs& in) {
  const auto& d = o.drop;
  json distractors = json::array();
  const std::vector<double> fractions = distractor_fractions(o.distractors);
  for (std::size_t k = 0; k < o.distractors.size(); ++k)
    distractors.push_back(
        {{"obj_id", k + 2},
         {"model", o.distractors[k].model},
         {"fraction", fractions[k]},
         {"diameter_mm", k < in.distractor_diameters.size() ? in.distractor_diameters[k] : 0.0}});
  return {{"synth_version", kSynthVersion},
          {"model", in.model},
          {"diameter_mm", in.diameter},
          {"distractors", distractors},
          {"seed", o.seed},
          {"noise", o.noise},
          {"sensor", sensor_model_json(o.sensor)},
          {"objects", d.objects},
          {"grid", {d.grid_x, d.grid_y}},
          {"bin_size_mm", {d.bin_size_mm.x(), d.bin_size_mm.y(), d.bin_size_mm.z()}},
          {"bin", bin_entry(o, in)},
          {"drop_height_mm", d.drop_height_mm},
          {"final_settle",
           {{"all_dynamic_until_at_rest", d.final_settle_all_dynamic},
            {"all_dynamic_s", d.final_all_dynamic_seconds}}},
          {"camera_height_mm", o.camera_height_mm},
          {"camera", camera_entry(o)},
          {"image", {o.width, o.height}},
          {"depth_scale", o.depth_scale}};
}

void check_or_write_manifest(const fs::path& out, const json& want) {
  const fs::path path = out / "synth.json";
  if (fs::exists(path)) {
    json have;
    try {
      have = json::parse(read_file_bytes(path));
    } catch (const json::exception&) {
      throw InputError(path.string() + " is not valid JSON: remove it or use another --out");
    }
    for (auto it = want.begin(); it != want.end(); ++it)
      if (!have.contains(it.key()) || have[it.key()] != it.value())
        throw InputError(fmt::format(
            "{} was made with {} = {}, this run asks for {}: use another --out to make a new "
            "dataset (same options resume or extend it)",
            out.string(), it.key(), have.contains(it.key()) ? have[it.key()].dump() : "nothing",
            it.value().dump()));
    return;
  }
  write_file_atomically(path, [&](std::ostream& s) { s << want.dump(1) << "\n"; });
}

std::string file_digest(const fs::path& path) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : read_file_bytes(path)) {
    h ^= std::uint8_t(c);
    h *= 0x100000001b3ull;
  }
  return fmt::format("{:016x}", h);
}

}  // namespace binpick
