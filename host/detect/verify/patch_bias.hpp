// The patch bias of verification: does the posed model's surface agree with the measured depth
// everywhere, or only on average? (docs/detect/verify.md, "Patch bias")
//
// ICP leaves a right pose's residuals as sensor noise: zero on average in every region of the
// part. A pose laid on a similar but different object (a bolt on the arm of a tee, a shaft on a
// bolt's shank) can fit as well on average, and at 5 % noise the widened inlier tolerance
// swallows the few millimetres where the shapes differ (the bolt's head standing above a pipe).
// Those millimetres show as regions whose residuals do not average out. So the model's points
// are grouped into patches (cells of a grid in the model's frame), and a patch is biased when
// its mean residual lies farther from zero than a dead band (small errors of a right pose, the
// model's own tessellation), by more than three standard errors (the noise seen in the pose's
// residuals over the square root of the patch's points). The score is multiplied by the share
// of tested patches that are not biased. Figures: docs/decisions/2026-11-24-patch-bias.md.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "host/detect/refine/model_patches.hpp"

namespace binpick {

struct PatchBias {
  std::uint32_t tested = 0;  // patches with at least min_points residuals
  std::uint32_t biased = 0;  // of those, the ones whose mean residual is off (see above)
  // The score's factor: the share of tested patches not biased (1 when none was tested).
  double factor() const { return tested == 0 ? 1.0 : 1.0 - double(biased) / double(tested); }
};

struct PatchBiasOptions {
  float dead_band = 0;             // mm: a mean residual within this is never biased
  std::uint32_t min_points = 15;   // residuals a patch needs to be tested
  float significance = 3;          // standard errors beyond the dead band
};

// residuals: one per model point (NaN: no residual), as pose_fit writes them.
PatchBias patch_bias(std::span<const float> residuals, const ModelPatches& patches,
                     const PatchBiasOptions& opt);

}  // namespace binpick
