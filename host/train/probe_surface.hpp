// The dense surface that verification probes are found on (lookalike_probes.hpp, edge_probes.hpp):
// the mesh sampled 16 times per probe voxel area, and the candidates, that sample voxel-subsampled
// at the probe voxel (a quarter of the model's voxel, both faces of a thin wall). The model's
// own points (a voxel apart) are too few where only a narrow band of the part tells poses apart.
#pragma once

#include "host/core/mesh.hpp"
#include "host/runtime/cl/cl_device.hpp"

namespace binpick {

inline constexpr float kProbeVoxelDivisor = 4.0f;

struct ProbeSurface {
  float probe_voxel = 0;  // mm
  PointCloud surface;     // the dense sample, unit normals
  PointCloud candidates;  // the surface a probe voxel apart, unit normals
};

// voxel_size > 0: the model's voxel (mm). Deterministic.
ProbeSurface probe_surface(const Mesh& mesh, float voxel_size,
                           ocl::Device& dev = ocl::Device::shared());

}  // namespace binpick
