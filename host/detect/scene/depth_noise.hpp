// The depth noise of an image, and the scene voxel it calls for.
//
// Why: the scene is subsampled with the model's voxel so that densities, and so votes, match
// (paper section III-C). Depth noise thickens every surface along the rays: at a sigma of 0.6
// voxel and more (3 % of the diameter at the default voxel), a surface fills two or three
// voxel layers instead of one, and the pairs (which grow with the square of the points) make
// voting slower with no more right poses found. Scene voxels longer along the camera's axis
// (the rays, near enough) at such noise keep about the points of a clean surface, and the same
// resolution across, which narrow parts need (larger cubic voxels lost a shaft's poses)
// (docs/detect/scene.md, "The scene voxel"; docs/decisions/2026-11-25-noise-voxel.md).
#pragma once

#include "host/detect/scene/depth_to_points.hpp"
#include "kernels/binpick_shared.h"

namespace binpick {

// Samples taken: every kNoiseRowStep-th row, every kNoiseColumnStep-th pixel of it.
inline constexpr std::uint32_t kNoiseRowStep = 4, kNoiseColumnStep = 2;
// Fewer samples than this (an image mostly without depth): no estimate (0).
inline constexpr std::size_t kMinNoiseSamples = 1000;

// The standard deviation of the depth noise, mm: from the second differences of depth along
// the rows, z(u-1) - 2 z(u) + z(u+1), taken where all three pixels have depth. On a smooth
// surface (a plane seen at any slant is nearly linear in z over three pixels) that is the noise
// alone, with sqrt(6) times its sigma; the median absolute value (times 1.4826, the normal
// distribution's MAD factor) ignores the depth steps between parts, which are a small share of
// the samples. A sample of the image (kNoiseRowStep, kNoiseColumnStep) is enough: the figure
// is one number for the whole image. 0 with fewer than kMinNoiseSamples samples.
double depth_noise_mm(DepthView depth, const bp_camera& cam);

// How many times longer along the camera's axis than the model's voxel the scene's are: 1 up
// to a sigma of kNoiseVoxelStart voxels, max_factor from kNoiseVoxelFull voxels on, linear
// between. max_factor <= 1: always 1.
inline constexpr double kNoiseVoxelStart = 0.45, kNoiseVoxelFull = 0.6;
double scene_voxel_factor(double noise_mm, double voxel_mm, double max_factor);

}  // namespace binpick
