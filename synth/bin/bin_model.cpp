#include "synth/bin/bin_model.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "host/core/error.hpp"

namespace binpick {
namespace {

using Box = Eigen::AlignedBox3d;
using V = Eigen::Vector3d;

void require(bool ok, const std::string& message) {
  if (!ok) throw InputError(message);
}

}  // namespace

void append_box(Mesh& mesh, const Box& box) {
  const V lo = box.min(), hi = box.max();
  // Each face: its outward axis and sign, and two in-plane axes ordered so that (a, b, n) is
  // right-handed: the corners (0,0), (1,0), (1,1), (0,1) in (a, b) run counter-clockwise seen
  // from outside.
  for (int axis = 0; axis < 3; ++axis)
    for (const int sign : {-1, 1}) {
      int a = (axis + 1) % 3, b = (axis + 2) % 3;
      if (sign < 0) std::swap(a, b);
      Eigen::Vector3f normal = Eigen::Vector3f::Zero();
      normal[axis] = float(sign);
      const auto base = std::uint32_t(mesh.positions.size());
      for (const auto& [ua, ub] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
        V p;
        p[axis] = sign > 0 ? hi[axis] : lo[axis];
        p[a] = ua ? hi[a] : lo[a];
        p[b] = ub ? hi[b] : lo[b];
        mesh.positions.push_back(p.cast<float>());
        mesh.normals.push_back(normal);
      }
      mesh.triangles.push_back({base, base + 1, base + 2});
      mesh.triangles.push_back({base, base + 2, base + 3});
    }
}

BinModel built_in_bin(const V& interior, const BuiltInBinWalls& walls) {
  require(interior.allFinite() && (interior.array() > 0).all(),
          "the bin interior needs three positive sizes");
  require(std::isfinite(walls.wall_mm) && walls.wall_mm >= 0.5 && walls.wall_mm <= 200,
          fmt::format("--bin-wall must be between 0.5 and 200 mm, got {}", walls.wall_mm));
  require(std::isfinite(walls.rim_mm) && walls.rim_mm >= 0 && walls.rim_mm <= 500,
          fmt::format("--bin-rim must be between 0 and 500 mm, got {}", walls.rim_mm));
  const double x = interior.x() / 2, y = interior.y() / 2, h = interior.z();
  const double t = walls.wall_mm, r = walls.rim_mm;
  BinModel bin;
  bin.boxes.emplace_back(V(-x - t, -y - t, -t), V(x + t, y + t, 0));  // floor, under the walls
  for (const double s : {-1.0, 1.0}) {
    // Walls along y (at +-x) run the full outer length; those along x fit between them.
    bin.boxes.emplace_back(V(s > 0 ? x : -x - t, -y - t, 0), V(s > 0 ? x + t : -x, y + t, h));
    bin.boxes.emplace_back(V(-x, s > 0 ? y : -y - t, 0), V(x, s > 0 ? y + t : -y, h));
  }
  if (r > 0) {
    // The lip: as thick as the walls, flush with their tops, reaching r beyond their outer faces.
    const double lo = h - std::min(t, h), xo = x + t, yo = y + t;
    for (const double s : {-1.0, 1.0}) {
      bin.boxes.emplace_back(V(s > 0 ? xo : -xo - r, -yo - r, lo),
                             V(s > 0 ? xo + r : -xo, yo + r, h));
      bin.boxes.emplace_back(V(-xo, s > 0 ? yo : -yo - r, lo), V(xo, s > 0 ? yo + r : -yo, h));
    }
  }
  bin.bounds.setEmpty();
  for (const Box& b : bin.boxes) {
    append_box(bin.mesh, b);
    bin.bounds.extend(b);
  }
  return bin;
}

BinModel bin_from_mesh(Mesh mesh) {
  require(!mesh.triangles.empty(), "the bin mesh has no triangles");
  BinModel bin;
  bin.bounds.setEmpty();
  for (const auto& p : mesh.positions) {
    require(p.allFinite(), "the bin mesh has a vertex that is not finite");
    bin.bounds.extend(p.cast<double>());
  }
  for (const auto& tri : mesh.triangles)
    for (const std::uint32_t i : tri)
      require(i < mesh.positions.size(), "the bin mesh has a triangle index out of range");
  require(mesh.normals.size() == mesh.positions.size(), "the bin mesh has no per-vertex normals");
  bin.mesh = std::move(mesh);
  bin.double_sided = true;
  return bin;
}

}  // namespace binpick
