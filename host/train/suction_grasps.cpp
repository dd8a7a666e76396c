#include "host/train/suction_grasps.hpp"

#include "host/train/ppf_model.hpp"

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
constexpr int kLeastSlip = 1;  // lip spacings a grasp may slip on its face and still seal
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

SuctionGraspOptions suction_grasp_options(double diameter, double voxel_size, double cup_diameter) {
  SuctionGraspOptions o;
  o.cup_diameter = cup_diameter > 0 ? cup_diameter : kDefaultCupRatio * diameter;
  o.flatness = kGraspFlatnessRatio * o.cup_diameter;
  o.spacing = 0.75 * voxel_size / kFitVoxelDivisor;
  o.apart = std::max(o.cup_diameter, kGraspApartRatio * diameter);
  return o;
}

bool cup_held(const PointGrid& index, const PointCloud& surface, const Eigen::Vector3d& p,
              const Eigen::Vector3d& n, const SuctionGraspOptions& o) {
  const double r = o.cup_diameter / 2;
  const Eigen::Vector3d u = across(n), v = n.cross(u);
  // The lip's points: 8 on the rim and 4 halfway in, in the cup's plane.
  std::vector<Eigen::Vector3d> at;
  for (int k = 0; k < kRimPoints; ++k)
    at.push_back(r * (std::cos(2 * kPi * k / kRimPoints) * u + std::sin(2 * kPi * k / kRimPoints) * v));
  for (int k = 0; k < kInnerPoints; ++k) {
    const double a = 2 * kPi * (k + 0.5) / kInnerPoints;
    at.push_back(r / 2 * (std::cos(a) * u + std::sin(a) * v));
  }
  std::vector<bool> held(at.size(), false);
  bool blocked = false;
  index.near(p.cast<float>(), float(r + o.spacing + o.flatness), [&](std::uint32_t j) {
    const CupCoords c = cup_coords(p, n, surface.points[j].cast<double>());
    if (blocked || c.radial > r + o.spacing) return;
    if (c.height > o.flatness && c.radial <= r) {
      blocked = true;
      return;
    }
    if (std::abs(c.height) > o.flatness || surface.normals[j].cast<double>().dot(n) < kSupportCos) return;
    for (std::size_t k = 0; k < at.size(); ++k)
      if ((c.in_plane - at[k]).norm() <= o.spacing) held[k] = true;
  });
  return !blocked && std::all_of(held.begin(), held.end(), [](bool h) { return h; });
}

std::vector<Grasp> find_suction_grasps(const PointCloud& surface, const SuctionGraspOptions& o) {
  if (!(o.cup_diameter > 0) || !(o.flatness > 0) || !(o.spacing > 0))
    throw std::logic_error("find_suction_grasps: cup diameter, flatness and spacing must be positive");
  const auto& pts = surface.points;
  const auto& nrm = surface.normals;
  if (pts.empty() || nrm.size() != pts.size()) return {};
  const double r = o.cup_diameter / 2;
  const PointGrid index(surface, cup_reach(o), 3);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : pts) centroid += p.cast<double>();
  centroid /= double(pts.size());
  std::vector<std::uint32_t> fitting;  // candidates whose disc the surface fills
  std::vector<bool> holds(pts.size(), false);
  for (std::uint32_t i = 0; i < pts.size(); ++i)
    if ((holds[i] = cup_held(index, surface, pts[i].cast<double>(), nrm[i].cast<double>(), o)))
      fitting.push_back(i);
  // How far a grasp may slip along its face and still seal (a detected pose is a few millimetres
  // off): the distance to the nearest point of the same face where the cup is not held (near an
  // edge, a hole, a bend), in lip spacings, up to the cup's radius.
  std::vector<int> slip(pts.size(), 0);
  const int most = int(r / o.spacing);
  for (const std::uint32_t i : fitting) {
    const Eigen::Vector3d p = pts[i].cast<double>(), n = nrm[i].cast<double>();
    double nearest = r;
    index.near(pts[i], float(r), [&](std::uint32_t j) {
      if (holds[j] || nrm[j].cast<double>().dot(n) < kSupportCos) return;
      const CupCoords c = cup_coords(p, n, pts[j].cast<double>());
      if (std::abs(c.height) <= o.flatness) nearest = std::min(nearest, c.radial);
    });
    slip[i] = std::min(most, int(nearest / o.spacing));
  }
  // A cup held only where it stands, not a lip spacing to any side, is held by the sampling's
  // luck: another sample of the same surface (eval's) or a pose a little off loses it.
  std::erase_if(fitting, [&](std::uint32_t i) { return slip[i] < kLeastSlip; });
  // Those that slip furthest first; then nearest the centroid (the pull through the part's
  // middle); index order on ties.
  std::vector<double> distance(pts.size());
  for (const std::uint32_t i : fitting) distance[i] = (pts[i].cast<double>() - centroid).norm();
  std::stable_sort(fitting.begin(), fitting.end(), [&](std::uint32_t a, std::uint32_t b) {
    return slip[a] != slip[b] ? slip[a] > slip[b] : distance[a] < distance[b];
  });

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
