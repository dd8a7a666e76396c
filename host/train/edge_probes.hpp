// The points just beyond a part's edges, for the edge step of verification
// (host/detect/verify/edge_step.hpp, read in the probe pass of lookalike_holes.hpp;
// docs/detect/verify.md, "Edge step") and the in-plane search (docs/detect/refine.md,
// "The in-plane score").
//
// A sheet (a plate 1.5 mm thick) lying on another steps down at its edges by one thickness,
// less than the verification's tolerance: the outline, which asks each outline cell whether
// the surface runs on within the tolerance, cannot tell that from a sheet surface that runs on,
// and is off for thin parts. A pose shifted or turned on a stack of sheets lies on surface
// everywhere, and only its edges are wrong: where the pose says the part ends, the sensor sees
// the same sheet run on. Averaged over a few hundred points the millimetre shows.
//
// An edge probe continues a face past its edge: q = p + margin e for a surface point p (normal
// n) and a direction e in p's tangent plane, kept where q lies at least 0.75 margin from every
// surface sample (free space just beyond the edge, around the outline and inside the holes)
// while the surface runs on from p for half a margin against e. The probe's normal is n.
// Deduplicated a probe voxel apart, evenly thinned to kMaxEdgeProbes. On a sheet that gives
// probes in the planes of its faces, around the outline and inside the holes, and probes that
// continue its rim walls above and below the faces (seen when the sheet is seen obliquely;
// without them fewer plates came out right: docs/decisions/2026-11-25-edge-step.md).
//
// Each probe has its kind: a *face probe* continues a surface that runs on for a whole margin
// behind p, a *rim probe* one narrower than that (a sheet's rim wall; the probe voxel a probe
// is kept from gives its kind). Only face probes go into the edge step. A rim probe hangs in
// the air a margin above the face, so where the face simply ran on it would still see the face
// behind it, h / cos farther along the ray (h >= 0.75 margin, cos between the face's normal and
// the ray): it reports a step wherever a face is seen obliquely, part edge or not, and plate
// poses laid on a robot arm's face won (docs/decisions/2026-12-02-edge-step-face-probes.md).
// The in-plane search uses both kinds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "host/core/mesh.hpp"
#include "host/runtime/cl/cl_device.hpp"
#include "host/train/probe_surface.hpp"

namespace binpick {

inline constexpr float kEdgeMarginVoxels = 2.0f;  // in probe voxels (probe_surface.hpp)
inline constexpr std::size_t kMaxEdgeProbes = 2048;

struct EdgeProbes {
  PointCloud cloud;               // model frame, unit normals
  std::vector<std::uint8_t> rim;  // per probe: 1 a rim probe, 0 a face probe
};

// The edge probes of the mesh (at most kMaxEdgeProbes); deterministic. voxel_size > 0: the
// model's voxel (mm); else none.
EdgeProbes find_edge_probes(const Mesh& mesh, float voxel_size,
                            ocl::Device& dev = ocl::Device::shared());
// The same on a probe surface already sampled (train shares one with the look-alike probes).
EdgeProbes find_edge_probes(const ProbeSurface& dense, ocl::Device& dev);

// The face probes among `probes` (rim: one kind per probe, or empty: all face probes), in order.
PointCloud face_probes(const PointCloud& probes, const std::vector<std::uint8_t>& rim);

}  // namespace binpick
