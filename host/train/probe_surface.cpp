#include "host/train/probe_surface.hpp"

#include <algorithm>
#include <cmath>

#include "host/core/cloud_input.hpp"
#include "host/train/surface_sampling.hpp"
#include "host/train/voxel_subsample.hpp"

namespace binpick {
namespace {

// Surface samples per probe voxel area: a point on the surface always finds a sample well
// inside a probe margin (1.5 probe voxels and more).
constexpr double kSurfaceSamplesPerProbeArea = 16.0;
// The dense surface is never larger than this (a part whose probe voxel is tiny against its
// area: the probes then thin out, and the margins still hold, since they scale with the voxel).
constexpr std::size_t kMaxSurfaceSamples = std::size_t(1) << 22;

}  // namespace

ProbeSurface probe_surface(const Mesh& mesh, float voxel_size, ocl::Device& dev) {
  ProbeSurface out;
  out.probe_voxel = voxel_size / kProbeVoxelDivisor;
  const double areas = surface_area(mesh) / (double(out.probe_voxel) * out.probe_voxel);
  const auto samples = static_cast<std::size_t>(
      std::clamp(std::ceil(kSurfaceSamplesPerProbeArea * areas), 1.0, double(kMaxSurfaceSamples)));
  // Another seed than training's sample: the probes need not coincide with the model's points.
  out.surface = with_unit_normals(sample_surface(mesh, samples, kSurfaceSamplingSeed + 1));
  out.candidates =
      with_unit_normals(voxel_subsample(dev, out.surface, out.probe_voxel, VoxelFaces::both).cloud);
  return out;
}

}  // namespace binpick
