// `binpick synth`: a BOP dataset of synthetic bins (paper III-A): decompose the part (and the
// distractors), drop them into the bin with Bullet, render the parts and the bin (depth,
// intensity, the scene cloud) with Vulkan, write.
// Each bin is written to a temporary directory and renamed into place when complete, so an
// interrupted run leaves only whole bins, and the same command again resumes where it stopped.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "synth/decompose/decompose.hpp"
#include "synth/part_mix.hpp"
#include "synth/physics/drop.hpp"
#include "synth/sensor/sensor_model.hpp"
#include "host/shards/shard.hpp"

namespace binpick {

// Whether the camera sees the bin: `full` renders it (its rim is often the highest thing in
// view, as in real bins); `none` renders the parts alone, as the paper did. The physics
// collides with the bin either way.
enum class BinRender { full, none };

struct SynthOptions {
  std::filesystem::path out;
  int bins = 30;
  std::uint64_t seed = 1;
  double noise = 0.0;               // sigma of the depth noise along the ray, fraction of diameter
  SensorModel sensor;               // ideal: the rendered depth (plus --noise); docs/sensor_model.md
  double camera_height_mm = 1000.0;  // along the optical axis to the centre of the bin floor
  double camera_tilt_deg = 0.0;      // about the bin's x axis (synth/camera_rig.hpp)
  double camera_roll_deg = 0.0;      // then about the optical axis (the bin turned in the image)
  std::optional<std::array<double, 4>> intrinsics;  // fx, fy, cx, cy; none: camera_for_bin
  std::uint32_t width = 1600, height = 900;
  double depth_scale = 0.1;         // mm per unit of the depth PNG
  bool write_cloud = true;
  bool write_masks = false;
  DropOptions drop;                 // objects, bin size and walls, waves, seed (set per bin)
  BinRender bin_render = BinRender::full;
  std::filesystem::path bin_mesh;   // a model file in the world frame (mm, floor at z = 0, z
                                    // up); empty: the built-in bin (drop.walls)
  std::vector<DistractorSpec> distractors;  // obj_ids 2, 3, ... in this order
  DecomposeOptions decompose;
  Shard shard;                      // --shard K/N: only bins K-1, K-1+N, ... (synth_shards.hpp)
  unsigned threads = 0;             // piles dropped at once (drops_ahead.hpp); 0: one per core
};

struct SynthSummary {
  int bins_made = 0, bins_skipped = 0;  // skipped: already complete from an earlier run
  int bins_missing = 0;                 // bins of other shards not made yet
  double seconds_decompose = 0, seconds_physics = 0, seconds_render = 0, seconds_write = 0;
};

struct Model;
// `model_description` (e.g. the --model argument) is recorded so a resumed run can tell that the
// existing dataset was made from the same input. `distractors` are the models of
// options.distractors, loaded, in the same order.
// `piles` (optional) keeps the simulated piles across calls that differ only in what does not
// move a part (noise, sensor, camera): `run`'s noise levels (pile_cache.hpp).
class PileCache;
SynthSummary synthesize(const Model& model, const std::string& model_description,
                        const SynthOptions& options, const std::vector<Model>& distractors = {},
                        PileCache* piles = nullptr);

// What a bin's pile depends on, as a string: the dataset's manifest without what only changes the
// picture (noise, sensor, camera, image, depth scale).
std::string physics_key(const nlohmann::json& manifest);

// Throws InputError for options no bin can be made with.
void validate_synth_options(const SynthOptions& options);

}  // namespace binpick
