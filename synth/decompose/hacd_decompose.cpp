// Runs HACD on a part normalised to a unit bounding-box diagonal and maps the hulls back to mm.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

// HACD's headers predate C++11's deprecation of implicit copy assignment.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-copy"
#include <hacdHACD.h>
#pragma GCC diagnostic pop

#include <LinearMath/btConvexHullComputer.h>

#include "host/core/error.hpp"
#include "synth/decompose/decompose.hpp"
#include "synth/decompose/hacd_simplify.hpp"
#include "synth/decompose/hull_cover.hpp"

namespace binpick {
namespace {

// HACD clusters triangles through shared vertices, so a mesh whose vertices were split per
// face (for normals, as STL and many glTF files are) would fall apart into single triangles.
// Weld bit-identical positions and drop the triangles that collapse.
HacdMesh weld(const Mesh& part) {
  struct BitsHash {
    std::size_t operator()(const std::array<std::uint32_t, 3>& b) const {
      return (std::size_t{b[0]} * 73856093u) ^ (std::size_t{b[1]} * 19349663u) ^
             (std::size_t{b[2]} * 83492791u);
    }
  };
  std::unordered_map<std::array<std::uint32_t, 3>, long, BitsHash> index_of;
  std::vector<long> remap(part.positions.size());
  HacdMesh welded;
  for (std::size_t i = 0; i < part.positions.size(); ++i) {
    const Eigen::Vector3f p = part.positions[i] + Eigen::Vector3f::Zero();  // -0 becomes +0
    std::array<std::uint32_t, 3> bits{};
    std::memcpy(bits.data(), p.data(), sizeof bits);
    auto [it, inserted] = index_of.try_emplace(bits, static_cast<long>(welded.points.size()));
    if (inserted) welded.points.push_back(p.cast<double>());
    remap[i] = it->second;
  }
  for (const auto& t : part.triangles) {
    const std::array<long, 3> w{remap[t[0]], remap[t[1]], remap[t[2]]};
    if (w[0] != w[1] && w[1] != w[2] && w[0] != w[2]) welded.triangles.push_back(w);
  }
  return welded;
}

// HACD's hulls may carry interior points (and exceed the vertex limit) when its incremental
// hull gives up; rebuilding each hull keeps only the extreme vertices the physics needs.
std::vector<Eigen::Vector3f> extreme_points(const std::vector<Eigen::Vector3d>& points) {
  btConvexHullComputer computer;
  computer.compute(points.data()->data(), sizeof(Eigen::Vector3d), static_cast<int>(points.size()),
                   0, 0);
  std::vector<Eigen::Vector3f> vertices;
  vertices.reserve(computer.vertices.size());
  for (int i = 0; i < computer.vertices.size(); ++i) {
    const btVector3& v = computer.vertices[i];
    vertices.emplace_back(float(v.x()), float(v.y()), float(v.z()));
  }
  return vertices;
}

// HACD returns some clusters as flat patches of surface (the built-in bracket: two planar
// quads and two slivers under 0.4 mm among 16 hulls, around its holes). They have no volume
// to collide with, and the drop's adaptive step, which keeps a part from passing through the
// thinnest hull, shrank to its floor for them: the 350-part drop was four times slower. Hulls
// thinner than this fraction of the part's diagonal are left out; the solid they border is
// in the other hulls.
constexpr double kMinThickness = 0.01;

void validate(const Mesh& part) {
  if (part.positions.empty() || part.triangles.empty())
    throw InputError("cannot decompose an empty mesh");
  for (const auto& p : part.positions)
    if (!p.allFinite()) throw InputError("mesh has a non-finite vertex position");
  for (const auto& t : part.triangles)
    for (std::uint32_t i : t)
      if (i >= part.positions.size())
        throw InputError("mesh triangle refers to vertex " + std::to_string(i) + " of " +
                         std::to_string(part.positions.size()));
}

}  // namespace

ConvexParts decompose_convex_uncached(const Mesh& part, const DecomposeOptions& options) {
  validate(part);
  const HacdMesh welded = weld(part);
  if (welded.triangles.empty()) throw InputError("mesh has only degenerate triangles");
  const HacdMesh mesh =
      simplify_for_hacd(welded, options.max_hacd_triangles, options.hacd_target_triangles);

  // HACD's concavity threshold depends on the model's scale (docs/synthesis.md): normalise to the
  // unit diagonal around the bounding-box centre, and undo that on the hulls.
  Eigen::Vector3d lo = mesh.points.front(), hi = lo;
  for (const auto& p : mesh.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const double diagonal = (hi - lo).norm();
  if (!(diagonal > 0.0)) throw InputError("mesh has zero extent");

  // HACD rescales the arrays it is given in place, so it gets its own copies.
  std::vector<HACD::Vec3<HACD::Real>> points;
  points.reserve(mesh.points.size());
  for (const auto& p : mesh.points) {
    const Eigen::Vector3d n = (p - centre) / diagonal;
    points.emplace_back(n.x(), n.y(), n.z());
  }
  std::vector<HACD::Vec3<long>> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);

  // HACD merges clusters while the concavity stays under the threshold, down to NClusters;
  // merge_hulls then joins the hulls that one hull covers almost as well. A part that still
  // has more than max_hulls (the built-in tee: 15) is decomposed again with no concavity limit
  // down to max_hulls, letting the hulls bridge its concavities (decompose.hpp).
  std::unique_ptr<HACD::HACD> hacd;
  std::vector<HACD::Vec3<HACD::Real>> in;  // HACD rescales its input in place: a fresh copy
  const auto run = [&](std::size_t clusters, double concavity) {
    hacd = std::make_unique<HACD::HACD>();
    in = points;
    hacd->SetPoints(in.data());
    hacd->SetNPoints(in.size());
    hacd->SetTriangles(triangles.data());
    hacd->SetNTriangles(triangles.size());
    hacd->SetCompacityWeight(options.compacity_weight);
    hacd->SetVolumeWeight(options.volume_weight);
    hacd->SetNClusters(clusters);
    hacd->SetNVerticesPerCH(options.max_hull_vertices);
    hacd->SetConcavity(concavity);
    hacd->SetAddExtraDistPoints(options.add_extra_dist_points);
    hacd->SetAddNeighboursDistPoints(options.add_neighbours_dist_points);
    hacd->SetAddFacesPoints(options.add_faces_points);
    if (!hacd->Compute()) throw InputError("HACD could not decompose the mesh");
  };
  // The hulls of the last run, in mm, thin ones left out, merged.
  const auto hulls = [&] {
    ConvexParts parts;
    for (std::size_t c = 0; c < hacd->GetNClusters(); ++c) {
      std::vector<HACD::Vec3<HACD::Real>> hull_points(hacd->GetNPointsCH(c));
      std::vector<HACD::Vec3<long>> hull_triangles(hacd->GetNTrianglesCH(c));
      if (hull_points.size() < 4 || !hacd->GetCH(c, hull_points.data(), hull_triangles.data()))
        continue;  // an empty cluster, or a flat one with no volume to collide with
      std::vector<Eigen::Vector3d> mm;
      mm.reserve(hull_points.size());
      for (const auto& q : hull_points)
        mm.push_back(Eigen::Vector3d(q.X(), q.Y(), q.Z()) * diagonal + centre);
      ConvexHull hull{extreme_points(mm)};
      if (hull.vertices.size() >= 4 && thinnest_extent(hull) >= kMinThickness * diagonal)
        parts.hulls.push_back(std::move(hull));
    }
    if (parts.hulls.empty()) throw InputError("HACD produced no convex hull with volume");
    if (options.merge.max_added_per_merge > 0.0) parts = merge_hulls(parts, options.merge);
    return parts;
  };
  run(options.min_clusters, options.concavity);
  ConvexParts parts = hulls();
  if (options.max_hulls > 0 && parts.hulls.size() > options.max_hulls) {
    run(std::max(options.max_hulls, options.min_clusters), std::numeric_limits<double>::max());
    parts = hulls();
  }
  if (options.max_uncovered > 0.0) parts = cover_mesh(parts, part, options.max_uncovered * diagonal);
  return parts;
}

}  // namespace binpick
