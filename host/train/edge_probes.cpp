#include "host/train/edge_probes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "host/core/cloud_input.hpp"
#include "host/core/two_halves.hpp"
#include "host/train/oriented_point_grid.hpp"
#include "host/train/probe_surface.hpp"
#include "host/train/voxel_subsample.hpp"

namespace binpick {
namespace {

constexpr int kDirections = 8;          // directions e tried in each candidate's tangent plane
static_assert(2 * kDirections <= 16, "a sample's directions and their rim flags fit 16 bits");
constexpr float kFreeRatio = 0.75f;     // a probe's distance to every surface sample, in margins
constexpr float kInwardRatio = 0.5f;    // how far the face must run on behind p, in margins
constexpr float kAnyFacing = -2.0f;     // a cosine every normal passes

}  // namespace

EdgeProbes find_edge_probes(const Mesh& mesh, float voxel_size, ocl::Device& dev) {
  if (!(voxel_size > 0)) return {};
  return find_edge_probes(probe_surface(mesh, voxel_size, dev), dev);
}

EdgeProbes find_edge_probes(const ProbeSurface& dense, ocl::Device& dev) {
  EdgeProbes out;
  if (!(dense.probe_voxel > 0)) return out;
  const float margin = kEdgeMarginVoxels * dense.probe_voxel;
  const OrientedPointGrid any(dense.surface, kFreeRatio * margin, kAnyFacing);
  const OrientedPointGrid face(dense.surface, 0.5f * dense.probe_voxel, kSameFacingCos);
  // Every dense sample is a candidate p (not only one a probe voxel): a probe needs p within a
  // quarter margin of the edge, a band narrower than the probe voxel. Per sample, a bit per
  // direction that gives a probe and one per direction whose probe is on a rim wall (two threads,
  // each its own samples; gathered in order below).
  const auto directions = [&](std::size_t i) {  // in the sample's tangent plane
    const Eigen::Vector3f& n = dense.surface.normals[i];
    const Eigen::Vector3f u = n.unitOrthogonal(), v = n.cross(u);
    std::array<Eigen::Vector3f, kDirections> e;
    for (int k = 0; k < kDirections; ++k) {
      const float a = float(2 * std::numbers::pi * k / kDirections);
      e[std::size_t(k)] = std::cos(a) * u + std::sin(a) * v;
    }
    return e;
  };
  std::vector<std::uint16_t> bits(dense.surface.points.size(), 0);
  in_two_halves(bits.size(), [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i) {
      const Eigen::Vector3f& p = dense.surface.points[i];
      const Eigen::Vector3f& n = dense.surface.normals[i];
      const auto e_of = directions(i);
      for (int k = 0; k < kDirections; ++k) {
        const Eigen::Vector3f& e = e_of[std::size_t(k)];
        if (any.matches(p + margin * e, n) || !face.matches(p - kInwardRatio * margin * e, n)) continue;
        bits[i] |= std::uint16_t(1u << k);
        // A face runs on for a whole margin behind p; a rim wall is narrower.
        if (!face.matches(p - margin * e, n)) bits[i] |= std::uint16_t(1u << (k + kDirections));
      }
    }
  });
  PointCloud found;
  std::vector<std::uint8_t> found_rim;
  for (std::size_t i = 0; i < bits.size(); ++i) {
    if (!bits[i]) continue;
    const auto e_of = directions(i);
    for (int k = 0; k < kDirections; ++k)
      if (bits[i] & (1u << k)) {
        found.points.push_back(dense.surface.points[i] + margin * e_of[std::size_t(k)]);
        found.normals.push_back(dense.surface.normals[i]);
        found_rim.push_back(bits[i] & (1u << (k + kDirections)) ? 1 : 0);
      }
  }
  if (found.points.empty()) return out;
  // One probe per probe voxel and facing (several candidates and directions reach the same
  // place); the one kept gives its kind.
  const VoxelSubsample sub = voxel_subsample(dev, found, dense.probe_voxel, VoxelFaces::both);
  const PointCloud probes = with_unit_normals(sub.cloud);
  // Evenly thinned to kMaxEdgeProbes: every k-th in the subsample's order, the same every run.
  const std::size_t step = (probes.points.size() + kMaxEdgeProbes - 1) / kMaxEdgeProbes;
  for (std::size_t k = 0; k < probes.points.size(); k += std::max<std::size_t>(step, 1)) {
    out.cloud.points.push_back(probes.points[k]);
    out.cloud.normals.push_back(probes.normals[k]);
    out.rim.push_back(found_rim[sub.kept[k]]);
  }
  return out;
}

PointCloud face_probes(const PointCloud& probes, const std::vector<std::uint8_t>& rim) {
  PointCloud out;
  for (std::size_t i = 0; i < probes.points.size(); ++i) {
    if (i < rim.size() && rim[i] != 0) continue;
    out.points.push_back(probes.points[i]);
    out.normals.push_back(probes.normals[i]);
  }
  return out;
}

}  // namespace binpick
