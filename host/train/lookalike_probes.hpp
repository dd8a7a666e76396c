// The points that tell a pose from its look-alikes (lookalikes.hpp). A plate turned over lies
// on the same outline and faces; only where one of the two has material and the other a hole
// does the depth image say which it is. Those places are found at training, on a dense sample
// of the mesh: a probe is a surface point p (normal n) whose image under the look-alike's
// inverse, S^-1 p, lies farther than a margin from any surface facing the same way (S^-1 n).
// At a pose P, the look-alike P S has no surface at P p, so the sensor sees the part there
// if P is right and looks through the part's hole if P S is (host/detect/verify/lookalike_holes.hpp).
//
// A probe must also lie inside a surface at least the margin wide around it (not on a sheet's
// hole wall, seen edge on over the hole, nor within the margin of an edge), so that a right pose
// a little off still has surface there.
//
// Density: the probes are the mesh voxel-subsampled at a quarter of the model's voxel (both
// faces of a thin wall); the surface they are tested against is sampled 16 times as densely,
// so that a point on the surface always finds a sample well inside the margin (1.5 probe
// voxels). The model's own points (a voxel apart) would leave a 16 mm hole in a 120 mm plate
// with only a handful of points, too few to average the sensor's noise out.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/mesh.hpp"
#include "host/train/probe_surface.hpp"
#include "host/runtime/cl/cl_device.hpp"

namespace binpick {

inline constexpr float kProbeMarginVoxels = 1.5f;     // in probe voxels
inline constexpr std::size_t kMaxProbesPerLookalike = 1024;  // evenly thinned beyond this

struct LookalikeProbes {
  PointCloud cloud;                // model frame, unit normals
  std::vector<std::uint32_t> twin;  // per probe: the index of its look-alike in `near`
};

// The probes of each look-alike in `near`, in its order, at most kMaxProbesPerLookalike each
// (deterministic). Empty if `near` is. voxel_size > 0: the model's voxel (mm).
LookalikeProbes find_lookalike_probes(const Mesh& mesh, float voxel_size,
                            const std::vector<Eigen::Isometry3d>& near,
                            ocl::Device& dev = ocl::Device::shared());
// The same on a probe surface already sampled (train shares one with the edge probes).
LookalikeProbes find_lookalike_probes(const ProbeSurface& dense,
                                      const std::vector<Eigen::Isometry3d>& near);

}  // namespace binpick
