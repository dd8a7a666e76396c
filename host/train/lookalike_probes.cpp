#include "host/train/lookalike_probes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "host/core/two_halves.hpp"
#include "host/train/oriented_point_grid.hpp"
#include "host/train/probe_surface.hpp"

namespace binpick {
namespace {

// Whether the surface facing n runs on for the margin around p in every direction along it (six
// points a margin away in p's tangent plane all lie on it, within half a probe voxel): a probe
// on a wall narrower than the margin (a sheet's hole wall, seen edge on over the hole) or at
// the margin of an edge would see the hole or what lies beyond the edge at a right pose as
// soon as the pose is a little off.
bool on_broad_surface(const OrientedPointGrid& fine, const Eigen::Vector3f& p,
                      const Eigen::Vector3f& n, float margin) {
  const Eigen::Vector3f u = n.unitOrthogonal(), v = n.cross(u);
  for (int k = 0; k < 6; ++k) {
    const float a = float(k * std::numbers::pi / 3);
    if (!fine.matches(p + margin * (std::cos(a) * u + std::sin(a) * v), n)) return false;
  }
  return true;
}

}  // namespace

LookalikeProbes find_lookalike_probes(const Mesh& mesh, float voxel_size,
                            const std::vector<Eigen::Isometry3d>& near, ocl::Device& dev) {
  if (near.empty() || !(voxel_size > 0)) return {};
  return find_lookalike_probes(probe_surface(mesh, voxel_size, dev), near);
}

LookalikeProbes find_lookalike_probes(const ProbeSurface& dense,
                                      const std::vector<Eigen::Isometry3d>& near) {
  LookalikeProbes out;
  if (near.empty() || !(dense.probe_voxel > 0)) return out;
  const float probe_voxel = dense.probe_voxel;
  const PointCloud& surface = dense.surface;
  const PointCloud& candidates = dense.candidates;
  const float margin = kProbeMarginVoxels * probe_voxel;
  const OrientedPointGrid grid(surface, margin, kSameFacingCos);
  const OrientedPointGrid fine(surface, 0.5f * probe_voxel, kSameFacingCos);
  for (std::uint32_t s = 0; s < near.size(); ++s) {
    const Eigen::Isometry3d inverse = near[s].inverse();
    std::vector<std::uint8_t> probe(candidates.points.size(), 0);  // two threads, each its own
    in_two_halves(probe.size(), [&](std::size_t first, std::size_t last) {
      for (std::size_t i = first; i < last; ++i) {
        const Eigen::Vector3d p = inverse * candidates.points[i].cast<double>();
        const Eigen::Vector3d n = inverse.linear() * candidates.normals[i].cast<double>();
        probe[i] = !grid.matches(p.cast<float>(), n.cast<float>()) &&
                   on_broad_surface(fine, candidates.points[i], candidates.normals[i], margin);
      }
    });
    std::vector<std::size_t> found;
    for (std::size_t i = 0; i < probe.size(); ++i)
      if (probe[i]) found.push_back(i);
    // Evenly thinned: every k-th in the subsample's order, which is the same on every run.
    const std::size_t step = (found.size() + kMaxProbesPerLookalike - 1) / kMaxProbesPerLookalike;
    for (std::size_t k = 0; k < found.size(); k += std::max<std::size_t>(step, 1)) {
      out.cloud.points.push_back(candidates.points[found[k]]);
      out.cloud.normals.push_back(candidates.normals[found[k]]);
      out.twin.push_back(s);
    }
  }
  return out;
}

}  // namespace binpick
