#include "synth/synthesize.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/formats/bop/bop_files.hpp"
#include "host/core/error.hpp"
#include "host/core/progress.hpp"
#include "host/core/atomic_file.hpp"
#include "host/core/read_file.hpp"
#include "host/core/diameter.hpp"
#include "host/formats/bop/bop_models.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "synth/render/bin_renderer.hpp"
#include "synth/bin_writer.hpp"
#include "synth/camera_rig.hpp"
#include "synth/seeds.hpp"
#include "host/core/timing.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

// Bumped whenever the same options make different bins (drop, decomposition, rendering), so a
// dataset is never resumed or extended with bins of another kind. 2: merged hulls, the
// sliding-window rest test and the final all-dynamic second.
constexpr int kSynthVersion = 2;

// Everything that shapes a bin except how many bins there are: a resumed or extended run must
// match it, or bins made with different settings would mix in one dataset.
json manifest(const SynthOptions& o, const std::string& model, double diameter) {
  const auto& d = o.drop;
  return {{"synth_version", kSynthVersion},
          {"model", model},
          {"diameter_mm", diameter},
          {"seed", o.seed},
          {"noise", o.noise},
          {"objects", d.objects},
          {"grid", {d.grid_x, d.grid_y}},
          {"bin_size_mm", {d.bin_size_mm.x(), d.bin_size_mm.y(), d.bin_size_mm.z()}},
          {"drop_height_mm", d.drop_height_mm},
          {"final_settle",
           {{"all_dynamic_until_at_rest", d.final_settle_all_dynamic},
            {"all_dynamic_s", d.final_all_dynamic_seconds}}},
          {"camera_height_mm", o.camera_height_mm},
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

std::vector<Eigen::Isometry3d> in_camera_frame(const std::vector<Eigen::Isometry3d>& world,
                                               const Eigen::Isometry3d& w2c) {
  std::vector<Eigen::Isometry3d> out;
  out.reserve(world.size());
  for (const auto& T : world) out.push_back(w2c * T);
  return out;
}

}  // namespace

void validate_synth_options(const SynthOptions& o) {
  if (o.out.empty()) throw InputError("--out: a dataset directory is required");
  if (o.bins < 1 || o.bins > 1000000) throw InputError("--bins must be between 1 and 1000000");
  if (!(o.noise >= 0 && o.noise <= 1)) throw InputError("--noise is a fraction of the diameter in [0, 1]");
  if (!(o.depth_scale > 0 && std::isfinite(o.depth_scale))) throw InputError("depth scale must be positive");
  if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
    throw InputError("image size must be between 16 and 16384 pixels a side");
  if (!(o.camera_height_mm > o.drop.bin_size_mm.z() && std::isfinite(o.camera_height_mm)))
    throw InputError("--camera-height must be above the bin's walls");
  validate_drop_options(o.drop);
}

SynthSummary synthesize(const Model& model, const std::string& model_description,
                        const SynthOptions& o) {
  validate_synth_options(o);
  const Mesh& part = model.mesh;
  const double diameter = exact_diameter(part.positions);
  fs::create_directories(o.out / "test");
  check_or_write_manifest(o.out, manifest(o, model_description, diameter));

  const RenderCamera camera = camera_for_bin(o.drop.bin_size_mm.x(), o.drop.bin_size_mm.y(),
                                             o.drop.bin_size_mm.z(), o.camera_height_mm, o.width,
                                             o.height);
  bop::write_camera(o.out / "camera.json",
                    {camera.fx, camera.fy, camera.cx, camera.cy, camera.width, camera.height,
                     o.depth_scale});
  write_bop_models(o.out, part, 1, model.symmetries);
  const Eigen::Isometry3d w2c = world_to_camera(o.camera_height_mm);

  SynthSummary summary;
  auto t0 = Clock::now();
  const ConvexParts hulls = decompose_convex(part, o.decompose);
  summary.seconds_decompose = seconds_since(t0);

  std::unique_ptr<BinRenderer> renderer;  // made on the first bin that is not already there
  const int waves = (o.drop.objects + o.drop.grid_x * o.drop.grid_y - 1) / (o.drop.grid_x * o.drop.grid_y);
  for (int b = 0; b < o.bins; ++b) {
    const fs::path scene = o.out / "test" / fmt::format("{:06d}", b);
    if (fs::exists(scene / "scene_gt.json")) {
      ++summary.bins_skipped;
      continue;
    }
    const fs::path staging = o.out / "test" / fmt::format(".{:06d}.partial", b);
    fs::remove_all(staging);
    fs::create_directories(staging);

    Progress progress(fmt::format("bin {}/{}", b + 1, o.bins), std::size_t(waves) + 1);
    DropOptions drop = o.drop;
    drop.seed = mix_seed(o.seed, 2 * std::uint64_t(b));
    t0 = Clock::now();
    const DropResult dropped = drop_parts(hulls, part, drop, [&](const DropProgress& p) {
      progress.update(std::size_t(p.wave), fmt::format("wave {}/{}: {} moving, {:.1f} s simulated",
                                                       p.wave + 1, p.waves, p.parts_moving,
                                                       p.simulated_seconds));
    });
    const double physics = seconds_since(t0);
    progress.update(std::size_t(waves), "rendering");

    t0 = Clock::now();
    const auto part_to_camera = in_camera_frame(dropped.poses, w2c);
    RenderOptions render_options;
    render_options.noise_sigma_mm = o.noise * diameter;
    render_options.seed = mix_seed(o.seed, 2 * std::uint64_t(b) + 1);
    if (!renderer) renderer = std::make_unique<BinRenderer>(part, camera);
    const RenderedBin rendered = renderer->render(part_to_camera, render_options);
    const double render = seconds_since(t0);

    t0 = Clock::now();
    write_bop_scene(staging, {rendered, camera, w2c, part_to_camera, o.depth_scale, o.write_cloud,
                              o.write_masks});
    fs::rename(staging, scene);
    const double write = seconds_since(t0);

    std::size_t visible = 0;
    for (auto px : rendered.px_visible) visible += px > 0;
    progress.finish(fmt::format(
        "{}: {} parts ({} visible), {}{:.1f} s simulated; physics {:.1f} s, render {:.2f} s, "
        "write {:.2f} s{}",
        scene.filename().string(), dropped.poses.size(), visible,
        dropped.stats.settled ? "at rest after " : "NOT at rest (time limit) after ",
        dropped.stats.simulated_seconds, physics, render, write,
        dropped.stats.message.empty() ? "" : "; " + dropped.stats.message));
    summary.seconds_physics += physics;
    summary.seconds_render += render;
    summary.seconds_write += write;
    ++summary.bins_made;
  }
  return summary;
}

}  // namespace binpick
