#include "synth/synthesize.hpp"
#include "synth/pile_cache.hpp"

#include <chrono>
#include <cmath>
#include <iostream>

#include <fmt/format.h>

#include "host/core/diameter.hpp"
#include "host/core/error.hpp"
#include "host/core/progress.hpp"
#include "host/core/timing.hpp"
#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/bop_models.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "synth/bin_writer.hpp"
#include "synth/camera_rig.hpp"
#include "synth/drops_ahead.hpp"
#include "host/formats/bop/test_targets.hpp"
#include "synth/physics/bin_capacity.hpp"
#include "synth/render/bin_renderer.hpp"
#include "synth/sensor/sensor_apply.hpp"
#include "synth/sensor/sensor_stage.hpp"
#include "host/runtime/vk/vk_context.hpp"
#include "synth/seeds.hpp"
#include "synth/synth_manifest.hpp"
#include "synth/synth_shards.hpp"

namespace binpick {
namespace {

// Says once per part when the physics' hulls come from a simplified mesh (hacd_simplify.hpp).
void note_simplified_hulls(const std::string& what, const Mesh& part, const DecomposeOptions& o) {
  if (part.triangles.size() <= o.max_hacd_triangles) return;
  std::cerr << fmt::format(
      "note: {}: {} triangles; its convex hulls for the physics come from the mesh simplified to "
      "{} triangles (grown to cover the mesh); rendering uses the mesh as it is\n",
      what, part.triangles.size(), o.hacd_target_triangles);
}

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::vector<Eigen::Isometry3d> in_camera_frame(const std::vector<Eigen::Isometry3d>& world,
                                               const Eigen::Isometry3d& w2c) {
  std::vector<Eigen::Isometry3d> out;
  out.reserve(world.size());
  for (const auto& T : world) out.push_back(w2c * T);
  return out;
}

CameraRig rig_of(const SynthOptions& o) {
  return {o.camera_height_mm, o.camera_tilt_deg, o.camera_roll_deg, o.width, o.height, o.intrinsics};
}

// The bin the options describe, loaded (a --bin-mesh file) or built.
std::shared_ptr<const BinModel> load_bin(const SynthOptions& o) {
  if (o.bin_mesh.empty()) return bin_of(o.drop);
  try {
    return std::make_shared<const BinModel>(bin_from_mesh(load_model(o.bin_mesh.string(), {})));
  } catch (const InputError& e) {
    throw InputError(fmt::format("--bin-mesh {}: {}", o.bin_mesh.string(), e.what()));
  }
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
  validate_camera_rig(rig_of(o));
  validate_drop_options(o.drop);
  if (o.bin_mesh.empty()) {
    built_in_bin(o.drop.bin_size_mm, o.drop.walls);  // throws for bad walls
  } else if (!fs::is_regular_file(o.bin_mesh)) {
    throw InputError(fmt::format("--bin-mesh {}: no such file", o.bin_mesh.string()));
  }
  kind_counts(o.drop.objects, o.distractors);  // throws for bad fractions
  check(o.sensor);
}

std::string physics_key(const nlohmann::json& manifest) {
  nlohmann::json physics = manifest;
  for (const char* picture_only :
       {"noise", "sensor", "camera_height_mm", "camera", "image", "depth_scale"})
    physics.erase(picture_only);
  return physics.dump();
}

SynthSummary synthesize(const Model& model, const std::string& model_description,
                        const SynthOptions& o, const std::vector<Model>& distractors,
                        PileCache* piles) {
  validate_synth_options(o);
  if (distractors.size() != o.distractors.size())
    throw InputError(fmt::format("synthesize: {} distractor models for {} distractors",
                                 distractors.size(), o.distractors.size()));
  // Kind k: the meshes (and hulls) in obj_id order, obj_id = k + 1.
  std::vector<Mesh> meshes{model.mesh};
  ManifestInputs inputs{model_description, exact_diameter(model.mesh.positions), {}, {}};
  for (const Model& m : distractors) {
    meshes.push_back(m.mesh);
    inputs.distractor_diameters.push_back(exact_diameter(m.mesh.positions));
  }
  if (!o.bin_mesh.empty()) inputs.bin_mesh_digest = file_digest(o.bin_mesh);
  const double diameter = inputs.diameter;
  check_part_size("--model " + model_description, diameter, o.drop.bin_size_mm);
  note_simplified_hulls("--model " + model_description, model.mesh, o.decompose);
  for (std::size_t k = 0; k < distractors.size(); ++k) {
    const std::string what = "--distractors " + o.distractors[k].model;
    check_part_size(what, inputs.distractor_diameters[k], o.drop.bin_size_mm);
    note_simplified_hulls(what, distractors[k].mesh, o.decompose);
  }
  const std::vector<int> counts = kind_counts(o.drop.objects, o.distractors);
  std::vector<const Mesh*> mesh_list;
  for (const Mesh& m : meshes) mesh_list.push_back(&m);
  check_bin_capacity(o.drop.objects, estimate_bin_capacity(o.drop.bin_size_mm, mesh_list, counts));
  fs::create_directories(o.out / "test");
  const nlohmann::json manifest = synth_manifest(o, inputs);
  check_or_write_manifest(o.out, manifest);
  const std::string pile_key = physics_key(manifest);
  const ShardRecord record = synth_shard_record(o.out, o.bins, o.shard.count);
  const auto done = [&](int b) { return bin_done(o.out, b); };
  if (o.shard.sharded()) {
    fs::create_directories(synth_state_dir(o.out));
    claim_shard_record(synth_shard_record_file(o.out), record, done);
  }

  DropOptions drop_options = o.drop;
  drop_options.bin = load_bin(o);
  const SceneView view = scene_view(rig_of(o), o.drop.bin_size_mm, drop_options.bin->bounds);
  const RenderCamera& camera = view.camera;
  const Eigen::Isometry3d& w2c = view.world_to_camera;
  bop::write_camera(o.out / "camera.json",
                    {camera.fx, camera.fy, camera.cx, camera.cy, camera.width, camera.height,
                     o.depth_scale});
  write_bop_models(o.out, model.mesh, 1, model.symmetries);
  write_bop_eval_model(o.out, model.mesh, 1, model.symmetries);
  for (std::size_t k = 0; k < distractors.size(); ++k) {
    write_bop_models(o.out, distractors[k].mesh, int(k) + 2, distractors[k].symmetries);
    write_bop_eval_model(o.out, distractors[k].mesh, int(k) + 2, distractors[k].symmetries);
  }

  SynthSummary summary;
  auto t0 = Clock::now();
  std::vector<ConvexParts> hulls;
  for (const Mesh& m : meshes) hulls.push_back(decompose_convex(m, o.decompose));
  std::vector<DropKind> kinds;
  for (std::size_t k = 0; k < meshes.size(); ++k) kinds.push_back({&hulls[k], &meshes[k]});
  summary.seconds_decompose = seconds_since(t0);

  std::unique_ptr<BinRenderer> renderer;  // made on the first bin that is not already there
  // Each part alone by the BOP toolkit's pixel centres, for scene_gt_info.json and the masks
  // (bin_camera.hpp: bop_toolkit_sampling). Back faces drawn, as the toolkit's renderer does.
  std::unique_ptr<BinRenderer> toolkit_renderer;
  std::unique_ptr<SensorStage> sensor;    // the same, for a structured-light sensor
  const bool structured_light = o.sensor.kind != SensorModel::Kind::ideal;
  SensorModel sensor_model = o.sensor;
  // --noise adds to the sensor's own noise, in quadrature; shadows and edges are found on the
  // ideal depth (docs/sensor_model.md).
  if (structured_light) sensor_model.added_sigma_mm = o.noise * diameter;
  const int waves = (o.drop.objects + o.drop.grid_x * o.drop.grid_y - 1) / (o.drop.grid_x * o.drop.grid_y);
  // Each bin's drop: its seed, and the mix of kinds from its own stream of that seed (without
  // distractors the orientations are those of a bin of one kind).
  const auto drop_request = [&](int b) {
    DropsAhead::Request r{drop_options, {}};
    r.drop.seed = mix_seed(o.seed, 2 * std::uint64_t(b));
    r.sequence = mixed_sequence(counts, mix_seed(r.drop.seed, 0));
    return r;
  };
  std::vector<int> todo;  // the bins to make, in order
  std::vector<DropsAhead::Request> to_drop;  // the piles of those not cached, in the same order
  for (int b = 0; b < o.bins; ++b) {
    if (!o.shard.owns(std::size_t(b))) continue;
    if (done(b)) {
      ++summary.bins_skipped;
      continue;
    }
    todo.push_back(b);
    if (!(piles && piles->find(pile_key, b))) to_drop.push_back(drop_request(b));
  }
  DropsAhead drops(kinds, std::move(to_drop), o.threads);
  for (const int b : todo) {
    const fs::path scene = o.out / "test" / fmt::format("{:06d}", b);
    const fs::path staging = o.out / "test" / fmt::format(".{:06d}.partial", b);
    fs::remove_all(staging);
    fs::create_directories(staging);

    Progress progress(fmt::format("bin {}/{}", b + 1, o.bins), std::size_t(waves) + 1);
    const DropResult* cached = piles ? piles->find(pile_key, b) : nullptr;
    const DropsAhead::Dropped dropped_now =
        cached ? DropsAhead::Dropped{}
               : drops.next([&](const DropProgress& p) {
                   progress.update(std::size_t(p.wave),
                                   fmt::format("wave {}/{}: {} moving, {:.1f} s simulated",
                                               p.wave + 1, p.waves, p.parts_moving,
                                               p.simulated_seconds));
                 });
    const DropResult& dropped = cached ? *cached : dropped_now.pile;
    if (piles && !cached) piles->store(pile_key, b, dropped);
    const double physics = dropped_now.seconds;
    progress.update(std::size_t(waves), "rendering");

    t0 = Clock::now();
    const auto part_to_camera = in_camera_frame(dropped.poses, w2c);
    RenderOptions render_options;
    render_options.noise_sigma_mm = structured_light ? 0.0 : o.noise * diameter;
    render_options.seed = mix_seed(o.seed, 2 * std::uint64_t(b) + 1);
    render_options.count_unoccluded = false;  // the toolkit's silhouettes below count them
    const bool show_bin = o.bin_render == BinRender::full;
    if (!renderer)
      renderer = std::make_unique<BinRenderer>(meshes, show_bin ? drop_options.bin.get() : nullptr,
                                               camera);
    RenderedBin rendered = renderer->render_scene(
        {part_to_camera, dropped.kinds, show_bin ? std::optional(w2c) : std::nullopt},
        render_options);
    if (!toolkit_renderer)
      toolkit_renderer =
          std::make_unique<BinRenderer>(meshes, nullptr, bop_toolkit_sampling(camera), false);
    const std::vector<PartSilhouette> silhouettes =
        toolkit_renderer->silhouettes({part_to_camera, dropped.kinds, std::nullopt});
    if (structured_light) {
      if (!sensor)
        sensor = std::make_unique<SensorStage>(vkrt::Context::shared(), camera.width, camera.height);
      apply_sensor_model(*sensor, camera, sensor_model, mix_seed(render_options.seed, 1), rendered);
    }
    const double render = seconds_since(t0);

    t0 = Clock::now();
    std::vector<int> obj_ids;
    for (const int k : dropped.kinds) obj_ids.push_back(k + 1);
    try {
      write_bop_scene(staging, {rendered, silhouettes, camera, w2c, part_to_camera, obj_ids, o.depth_scale,
                                o.write_cloud, o.write_masks});
      fs::rename(staging, scene);
    } catch (...) {
      // A full disk: give the space of the half-written bin back (a kill leaves it to the
      // next run, which replaces it).
      std::error_code ignored;
      fs::remove_all(staging, ignored);
      throw;
    }
    const double write = seconds_since(t0);

    std::size_t visible = 0;
    for (auto px : rendered.px_visible) visible += px > 0;
    progress.finish(fmt::format(
        "{}: {} parts ({} visible), {}{:.1f} s simulated; physics {}, render {:.2f} s, "
        "write {:.2f} s{}{}",
        scene.filename().string(), dropped.poses.size(), visible,
        dropped.stats.settled ? "at rest after " : "NOT at rest (time limit) after ",
        dropped.stats.simulated_seconds,
        cached ? std::string("reused (the pile of an earlier noise level)")
               : fmt::format("{:.1f} s", physics),
        render, write,
        dropped.stats.sheet_pile
            ? fmt::format("; sheet parts (a hull under {} mm): not released at the end, {} solver "
                          "iterations",
                          o.drop.sheet_hull_mm, o.drop.sheet_solver_iterations)
            : "",
        dropped.stats.message.empty() ? "" : "; " + dropped.stats.message));
    summary.seconds_physics += physics;
    summary.seconds_render += render;
    summary.seconds_write += write;
    ++summary.bins_made;
  }
  summary.bins_missing = int(missing_work(record, done).items.size());
  // Over every scene of the dataset, also those of an earlier run that were kept; only once the
  // whole batch is there (with shards, the last one writes it: the same bytes as unsharded).
  if (summary.bins_missing == 0) bop::write_test_targets(o.out);
  return summary;
}

}  // namespace binpick
