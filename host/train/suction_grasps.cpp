#include "host/train/suction_grasps.hpp"

#include "host/core/point_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

namespace binpick {
namespace {

constexpr double kSupportCos = 0.7071067811865476;  // cos 45 degrees: a face a cup's lip follows
constexpr double kSameFaceCos = 0.984807753012208;  // cos 10 degrees: grasps spread on one face
constexpr int kRimPoints = 8, kInnerPoints = 4;    // where the cup's lip and middle must find surface
constexpr double kPi = std::numbers::pi;

// Where q lies relative to the cup on p's plane: height above it, distance from the axis.
struct CupCoords {
  double height, radial;
  Eigen::Vector3d in_plane;
};

CupCoords cup_coords(const Eigen::Vector3d& p, const Eigen::Vector3d& n, const Eigen::Vector3d& q) {
  const Eigen::Vector3d d = q - p;
  const double h = d.dot(n);
  const Eigen::Vector3d flat = d - h * n;
  return {h, flat.norm(), flat};
}

}  // namespace

std::vector<Grasp> find_suction_grasps(const PointCloud& surface, const SuctionGraspOptions& o) {
  if (!(o.cup_diameter > 0) || !(o.flatness > 0) || !(o.spacing > 0))
    throw std::logic_error("find_suction_grasps: cup diameter, flatness and spacing must be positive");
  const auto& pts = surface.points;
  const auto& nrm = surface.normals;
  if (pts.empty() || nrm.size() != pts.size()) return {};
  const double r = o.cup_diameter / 2;
  const float reach = float(r + o.spacing + o.flatness);  // a lip point's support lies within
  const PointGrid index(surface, reach, 3);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : pts) centroid += p.cast<double>();
  centroid /= double(pts.size());

  // The lip's points (8 on the rim, 4 halfway in) in the cup's plane, as (radial, angle).
  std::vector<Eigen::Vector2d> lip;
  for (int k = 0; k < kRimPoints; ++k) lip.emplace_back(r, 2 * kPi * k / kRimPoints);
  for (int k = 0; k < kInnerPoints; ++k) lip.emplace_back(r / 2, 2 * kPi * (k + 0.5) / kInnerPoints);
  std::vector<std::uint32_t> fitting;  // candidates whose disc the surface fills
  for (std::uint32_t i = 0; i < pts.size(); ++i) {
    const Eigen::Vector3d p = pts[i].cast<double>(), n = nrm[i].cast<double>();
    const Eigen::Vector3d u = across(n), v = n.cross(u);
    std::vector<Eigen::Vector3d> at;
    for (const auto& l : lip) at.push_back(l.x() * (std::cos(l.y()) * u + std::sin(l.y()) * v));
    std::vector<bool> held(lip.size(), false);
    bool blocked = false;
    index.near(pts[i], reach, [&](std::uint32_t j) {
      const CupCoords c = cup_coords(p, n, pts[j].cast<double>());
      if (blocked || c.radial > r + o.spacing) return;
      if (c.height > o.flatness && c.radial <= r) {
        blocked = true;
        return;
      }
      if (std::abs(c.height) > o.flatness || nrm[j].cast<double>().dot(n) < kSupportCos) return;
      for (std::size_t k = 0; k < at.size(); ++k)
        if ((c.in_plane - at[k]).norm() <= o.spacing) held[k] = true;
    });
    if (!blocked && std::all_of(held.begin(), held.end(), [](bool h) { return h; }))
      fitting.push_back(i);
  }
  // Nearest the centroid first (the pull through the part's middle); index order on ties.
  std::vector<double> distance(pts.size());
  for (const std::uint32_t i : fitting) distance[i] = (pts[i].cast<double>() - centroid).norm();
  std::stable_sort(fitting.begin(), fitting.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return distance[a] < distance[b]; });

  const double apart = o.apart > 0 ? o.apart : r;
  std::vector<Grasp> grasps;
  for (const std::uint32_t i : fitting) {
    if (grasps.size() >= o.max_grasps) break;
    const Eigen::Vector3d p = pts[i].cast<double>(), n = nrm[i].cast<double>();
    const bool crowded = std::any_of(grasps.begin(), grasps.end(), [&](const Grasp& g) {
      return -g.approach.dot(n) > kSameFaceCos && (g.point - p).norm() < apart;
    });
    if (crowded) continue;
    // Nothing of the part above the face anywhere over the cup, however far up (a bracket's
    // other leg over this one).
    const bool covered = std::any_of(pts.begin(), pts.end(), [&](const Eigen::Vector3f& q) {
      const CupCoords c = cup_coords(p, n, q.cast<double>());
      return c.height > o.flatness && c.radial <= r;
    });
    if (covered) continue;
    Grasp g;
    g.kind = Grasp::Kind::suction;
    g.point = p;
    g.approach = -n;
    g.closing = across(g.approach);
    g.size = o.cup_diameter;
    grasps.push_back(g);
  }
  return grasps;
}

}  // namespace binpick
