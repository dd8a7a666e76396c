// `binpick synth`: a BOP dataset of synthetic bins (paper III-A): decompose the part, drop it
// into the bin with Bullet, render depth, intensity and the scene cloud with Vulkan, write.
// Each bin is written to a temporary directory and renamed into place when complete, so an
// interrupted run leaves only whole bins, and the same command again resumes where it stopped.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "synth/decompose/decompose.hpp"
#include "synth/physics/drop.hpp"

namespace binpick {

struct SynthOptions {
  std::filesystem::path out;
  int bins = 30;
  std::uint64_t seed = 1;
  double noise = 0.0;               // sigma of the depth noise along the ray, fraction of diameter
  double camera_height_mm = 1000.0;
  std::uint32_t width = 1600, height = 900;
  double depth_scale = 0.1;         // mm per unit of the depth PNG
  bool write_cloud = true;
  bool write_masks = false;
  DropOptions drop;                 // objects, bin size, waves, seed (set per bin)
  DecomposeOptions decompose;
};

struct SynthSummary {
  int bins_made = 0, bins_skipped = 0;  // skipped: already complete from an earlier run
  double seconds_decompose = 0, seconds_physics = 0, seconds_render = 0, seconds_write = 0;
};

struct Model;
// `model_description` (e.g. the --model argument) is recorded so a resumed run can tell that the
// existing dataset was made from the same input.
SynthSummary synthesize(const Model& model, const std::string& model_description,
                        const SynthOptions& options);

// Throws InputError for options no bin can be made with.
void validate_synth_options(const SynthOptions& options);

}  // namespace binpick
