#include "host/detect/params/bin_mesh_interior.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick {

double ray_triangle_distance(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                             const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-12 * e1.norm() * e2.norm()) return -1;  // parallel or degenerate
  const Eigen::Vector3d s = o - a;
  const double u = s.dot(p) / det;
  if (u < 0 || u > 1) return -1;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0 || u + v > 1) return -1;
  const double t = e2.dot(q) / det;
  return t > 0 ? t : -1;
}

Eigen::Vector3d bin_interior_from_mesh(const Mesh& mesh) {
  double top = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d extent = Eigen::Vector3d::Zero();
  for (const auto& p : mesh.positions) {
    top = std::max(top, double(p.z()));
    extent = extent.cwiseMax(p.cast<double>().cwiseAbs());
  }
  if (!(top > 0))
    throw InputError("the bin mesh has nothing above its floor (z = 0): expected mm, the origin "
                     "at the centre of the interior floor, z up (as synth --bin-mesh)");
  // Rays 1/64 of the middle half apart across (a wire basket's bars are a few mm wide), at 5
  // heights.
  constexpr int kAcross = 33, kHeights = 5;
  double half[2][2];  // [axis x, y][side +, -]
  for (int axis = 0; axis < 2; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int across = 1 - axis;
      Eigen::Vector3d dir = Eigen::Vector3d::Zero();
      dir[axis] = side == 0 ? 1 : -1;
      double nearest = std::numeric_limits<double>::infinity();
      for (int i = 0; i < kAcross; ++i)
        for (int j = 0; j < kHeights; ++j) {
          Eigen::Vector3d o = Eigen::Vector3d::Zero();
          o[across] = (-0.25 + 0.5 * i / (kAcross - 1)) * extent[across];
          o.z() = (0.2 + 0.6 * j / (kHeights - 1)) * top;
          for (const auto& tri : mesh.triangles) {
            const double t = ray_triangle_distance(
                o, dir, mesh.positions[tri[0]].cast<double>(), mesh.positions[tri[1]].cast<double>(),
                mesh.positions[tri[2]].cast<double>());
            if (t > 0) nearest = std::min(nearest, t);
          }
        }
      if (!std::isfinite(nearest))
        throw InputError(fmt::format(
            "the bin mesh has no wall along {}{} from the middle of its floor: expected mm, the "
            "origin at the centre of the interior floor, z up (as synth --bin-mesh)",
            side == 0 ? "+" : "-", "xy"[axis]));
      half[axis][side] = nearest;
    }
  const double w = half[0][0] + half[0][1], d = half[1][0] + half[1][1];
  return {std::max(w, d), std::min(w, d), top};
}

}  // namespace binpick
