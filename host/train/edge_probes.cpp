#include "host/train/edge_probes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "host/core/cloud_input.hpp"
#include "host/train/oriented_point_grid.hpp"
#include "host/train/probe_surface.hpp"
#include "host/train/voxel_subsample.hpp"

namespace binpick {
namespace {

constexpr int kDirections = 8;          // directions e tried in each candidate's tangent plane
constexpr float kFreeRatio = 0.75f;     // a probe's distance to every surface sample, in margins
constexpr float kInwardRatio = 0.5f;    // how far the face must run on behind p, in margins
constexpr float kAnyFacing = -2.0f;     // a cosine every normal passes

}  // namespace

PointCloud find_edge_probes(const Mesh& mesh, float voxel_size, ocl::Device& dev) {
  PointCloud found;
  if (!(voxel_size > 0)) return found;
  const ProbeSurface dense = probe_surface(mesh, voxel_size, dev);
  const float margin = kEdgeMarginVoxels * dense.probe_voxel;
  const OrientedPointGrid any(dense.surface, kFreeRatio * margin, kAnyFacing);
  const OrientedPointGrid face(dense.surface, 0.5f * dense.probe_voxel, kSameFacingCos);
  // Every dense sample is a candidate p (not only one a probe voxel): a probe needs p within a
  // quarter margin of the edge, a band narrower than the probe voxel.
  for (std::size_t i = 0; i < dense.surface.points.size(); ++i) {
    const Eigen::Vector3f& p = dense.surface.points[i];
    const Eigen::Vector3f& n = dense.surface.normals[i];
    const Eigen::Vector3f u = n.unitOrthogonal(), v = n.cross(u);
    for (int k = 0; k < kDirections; ++k) {
      const float a = float(2 * std::numbers::pi * k / kDirections);
      const Eigen::Vector3f e = std::cos(a) * u + std::sin(a) * v;
      const Eigen::Vector3f q = p + margin * e;
      if (any.matches(q, n) || !face.matches(p - kInwardRatio * margin * e, n)) continue;
      found.points.push_back(q);
      found.normals.push_back(n);
    }
  }
  if (found.points.empty()) return found;
  // One probe per probe voxel and facing (several candidates and directions reach the same place).
  PointCloud probes =
      with_unit_normals(voxel_subsample(dev, found, dense.probe_voxel, VoxelFaces::both).cloud);
  if (probes.points.size() <= kMaxEdgeProbes) return probes;
  // Evenly thinned: every k-th in the subsample's order, which is the same on every run.
  PointCloud thinned;
  const std::size_t step = (probes.points.size() + kMaxEdgeProbes - 1) / kMaxEdgeProbes;
  for (std::size_t k = 0; k < probes.points.size(); k += step) {
    thinned.points.push_back(probes.points[k]);
    thinned.normals.push_back(probes.normals[k]);
  }
  return thinned;
}

}  // namespace binpick
