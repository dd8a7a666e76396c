// The subsampled neighbourhood of one hypothesis, with normals computed only where they are
// needed: voting uses only the thousand or two points left after cropping and subsampling a
// hypothesis, and normals over the whole image cost far more (docs/detect/scene.md, "Normals";
// docs/decisions/2026-11-28-lazy-normals.md).
//
// The result is exactly voxel_subsample(crop_sphere(scene with normals everywhere)) -- the
// crop's points that have a valid normal, subsampled -- but the normals are computed lazily:
//   1. crop the pixels whose point lies in the sphere (no normal needed): the set S;
//   2. subsample S; compute normals of the kept points and of one extreme point per axis
//      and side (they fix the voxel grid's origin and size);
//   3. if all of them are valid, subsampling the valid points V of S gives the same result:
//      V has the same extremes (so the same grid) and every voxel's winner in S (nearest its
//      centre, then lowest index) is in V, so it wins in V too; otherwise compute the normals
//      of every point in the voxels whose winner has none (their next winners), drop the
//      invalid ones from S and go to 2. Usually one or two extra rounds; after a few, all
//      normals of S are computed at once.
#pragma once

#include <cstddef>

#include "host/detect/scene/scene_crop.hpp"
#include "host/detect/scene/scene_normals.hpp"
#include "host/detect/scene/scene_prepare.hpp"
#include "host/core/timing.hpp"
#include "host/train/voxel_subsample.hpp"

namespace binpick {

struct NeighbourhoodSample {
  PointCloud cloud;               // subsampled points with unit normals, pixel order
  std::size_t cropped = 0;        // pixels with data inside the sphere
  std::size_t normals = 0;        // normals computed
  std::size_t rounds = 0;         // subsampling rounds
};

// Rounds of step 2 before all remaining normals are computed at once.
inline constexpr std::size_t kLazyNormalRounds = 3;

// Routine: on a prepared scene on the device (normals not needed). Appends the stages "crop",
// "subsample" and "normals" to timings if given. With a "may be used" mask (scene_mask.hpp) only
// the pixels it keeps enter the crop; normals are still fitted to every measured point near a
// kept one (a part's normal next to the bin's wall is the part's, whatever the mask says).
// depth_stretch >= 1: the voxels are that many times longer along the camera's z axis (noisy
// depth thickens surfaces along the rays; depth_noise.hpp), the same across.
NeighbourhoodSample sample_neighbourhood(const PreparedScene& scene, const CropOptions& crop,
                                         const NormalOptions& normals, float voxel_size,
                                         StageTimings* timings = nullptr,
                                         const ocl::Buffer<std::uint8_t>* mask = nullptr,
                                         float depth_stretch = 1.0f);

// Reference: all normals of the image, crop_sphere_reference, voxel_subsample_reference; with a
// mask, the masked pixels' normals are dropped before the crop.
NeighbourhoodSample sample_neighbourhood_reference(const PointImage& points,
                                                   const CropOptions& crop,
                                                   const NormalOptions& normals,
                                                   float voxel_size,
                                                   const std::vector<std::uint8_t>* mask = nullptr,
                                                   float depth_stretch = 1.0f);

}  // namespace binpick
