#include "host/train/symmetry_detect.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "host/core/angles.hpp"
#include "host/core/diameter.hpp"
#include "host/core/error.hpp"
#include "host/train/oriented_point_grid.hpp"
#include "host/train/surface_sampling.hpp"

namespace binpick {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Reference samples this far apart (of the diameter) leave a point of the surface without a
// sample within half the distance tolerance with probability exp(-pi 1.25^2) = 0.7 %, and
// without one within the whole tolerance practically never.
constexpr double kSpacingRatio = 0.004;
constexpr std::size_t kMinSamples = 20000, kMaxSamples = 400000;
constexpr std::size_t kTestPoints = 2000;
constexpr std::uint64_t kTestSeed = kSurfaceSamplingSeed ^ 0x73796d6d65747279ull;  // "symmetry"

// Not fractions of a turn: a surface that passes all four is round about the axis, not n-fold.
constexpr double kContinuousAngles[] = {0.37, 1.1, 2.3, 3.9};

// Two moments of inertia are equal when they differ by less than this fraction of the largest
// (a generous figure: a plane wrongly taken as degenerate costs a scan, not a symmetry).
constexpr double kEqualMoments = 1e-2;

constexpr double kScanStep = 0.5 * kDeg;    // perpendicular half-turn axes, coarse
constexpr int kRefineSteps = 10;            // per coarse step on either side
constexpr std::size_t kScanPoints = 128;    // test points of the coarse scan
constexpr std::size_t kScanMisses = 12;     // a coarse step passes with at most this many
constexpr std::size_t kRefinePoints = 512;  // test points of the refinement
constexpr std::size_t kMaxRuns = 16;        // runs of passing coarse steps refined per axis
constexpr double kSameAxisDeg = 1.0;        // candidate axes (up to sign) merged within
// Products of generators merged within this: the elements of the groups found differ by 7.5
// degrees or more (n <= 24, and half turns scanned at pi / n), while a generator found by the
// scan may be a fraction of a degree off and products add its error up.
constexpr std::size_t kFeatureAxes = 12;  // of each kind when all moments are equal

struct Moments {
  Vector3d centroid;
  Matrix3d covariance;
};

// Exact moments of the surface (area measure): per triangle (a, b, c) of area A,
// integral x = A s / 3 and integral x x^T = A (a a^T + b b^T + c c^T + s s^T) / 12, s = a + b + c.
// Relative to the first vertex, so large coordinates do not cancel.
Moments surface_moments(const Mesh& mesh) {
  const Vector3d origin = mesh.positions.front().cast<double>();
  double area = 0;
  Vector3d first = Vector3d::Zero();
  Matrix3d second = Matrix3d::Zero();
  for (const auto& t : mesh.triangles) {
    const Vector3d a = mesh.positions[t[0]].cast<double>() - origin;
    const Vector3d b = mesh.positions[t[1]].cast<double>() - origin;
    const Vector3d c = mesh.positions[t[2]].cast<double>() - origin;
    const double A = 0.5 * (b - a).cross(c - a).norm();
    const Vector3d s = a + b + c;
    area += A;
    first += A / 3 * s;
    second +=
        A / 12 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  const Vector3d mean = first / area;
  return {origin + mean, second / area - mean * mean.transpose()};
}

Matrix3d rotation(const Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Matrix3d half_turn(const Vector3d& axis) {
  const Vector3d u = axis.normalized();
  return 2 * u * u.transpose() - Matrix3d::Identity();
}

double rotation_distance_deg(const Matrix3d& A, const Matrix3d& B) {
  const Eigen::Quaterniond qa(A), qb(B);
  return 2 * std::acos(std::min(1.0, std::fabs(qa.dot(qb)))) / kDeg;
}

bool same_axis(const Vector3d& a, const Vector3d& b) {
  return std::fabs(a.normalized().dot(b.normalized())) >= std::cos(kSameAxisDeg * kDeg);
}

// The direction with its largest component positive, so an axis prints the same either way.
Vector3d canonical(const Vector3d& v) {
  Eigen::Index k;
  v.cwiseAbs().maxCoeff(&k);
  return v[k] < 0 ? Vector3d(-v) : v;
}

// A unit vector perpendicular to a.
Vector3d perpendicular(const Vector3d& a) {
  const Vector3d helper = std::fabs(a.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
  return a.cross(helper).normalized();
}

// Whether rotations about the centroid map the surface onto itself (see the header).
class SurfaceTest {
 public:
  SurfaceTest(const Mesh& mesh, const Vector3d& centre, double diameter, double area)
      : grid_(reference(mesh, diameter, area), float(kSymmetryDistanceRatio * diameter),
              float(std::cos(kSymmetryNormalDeg * kDeg))),
        centre_(centre) {
    const PointCloud test = sample_surface(mesh, kTestPoints, kTestSeed);
    for (std::size_t i = 0; i < test.points.size(); ++i) {
      points_.push_back(test.points[i].cast<double>() - centre);
      normals_.push_back(test.normals[i].cast<double>());
    }
  }

  // Test points of the first `count` that land off the surface, counting stopped past `stop`.
  std::size_t misses(const Matrix3d& R, std::size_t count, std::size_t stop) const {
    std::size_t missed = 0;
    for (std::size_t i = 0; i < std::min(count, points_.size()) && missed <= stop; ++i)
      if (!grid_.matches((R * points_[i] + centre_).cast<float>(), (R * normals_[i]).cast<float>()))
        ++missed;
    return missed;
  }

  bool accepts(const Matrix3d& R) const {
    const auto allowed = std::size_t(kSymmetryMissRatio * double(points_.size()));
    return misses(R, points_.size(), allowed) <= allowed;
  }

  double mean_plane_distance(const Matrix3d& R, std::size_t count) const {
    double sum = 0;
    count = std::min(count, points_.size());
    for (std::size_t i = 0; i < count; ++i)
      sum += grid_.plane_distance((R * points_[i] + centre_).cast<float>(),
                                  (R * normals_[i]).cast<float>());
    return sum / double(count);
  }

 private:
  static PointCloud reference(const Mesh& mesh, double diameter, double area) {
    const double spacing = kSpacingRatio * diameter;
    const double wanted = std::ceil(area / (spacing * spacing));
    const auto count = std::size_t(std::clamp(wanted, double(kMinSamples), double(kMaxSamples)));
    return sample_surface(mesh, count);
  }

  OrientedPointGrid grid_;
  Vector3d centre_;
  std::vector<Vector3d> points_, normals_;
};

struct AxisResult {
  Vector3d axis;
  bool continuous = false;
  int order = 1;  // n of the largest n-fold rotation that passed; 1: none
};

AxisResult examine_axis(const SurfaceTest& test, const Vector3d& axis) {
  AxisResult r{axis};
  r.continuous = std::all_of(std::begin(kContinuousAngles), std::end(kContinuousAngles),
                             [&](double angle) { return test.accepts(rotation(axis, angle)); });
  if (r.continuous) return r;
  // Every turn of the group, not only the first: near 2 pi / n the orders lie a degree or two
  // apart, within the test's tolerance (a 14-tooth gear on a round shaft passes a 24-degree
  // turn, a fifteenth, and fails 48), so the largest n whose first turn passes may be no group.
  // Both ways round: the test samples the surface, and on a part that is nearly round about
  // the axis (a cap screw, whose 6 mm hexagonal socket is all that is not round) a turn can
  // pass and its inverse fail by a few test points; the screw came out eightfold with only
  // six of the seven turns (+45 degrees but not -45), a set that is no group.
  const auto all_turns_pass = [&](int n) {
    for (int k = 1; k < n; ++k)
      if (!test.accepts(rotation(axis, 2 * std::numbers::pi * k / n))) return false;
    return true;
  };
  for (int n = kSymmetryMaxFold; n >= 2; --n)
    if (all_turns_pass(n)) {
      r.order = n;
      break;
    }
  return r;
}

// Half turns about axes perpendicular to `axis` that pass, scanning the directions
// cos(psi) start + sin(psi) (axis x start) for psi in [0, period).
std::vector<Matrix3d> perpendicular_half_turns(const SurfaceTest& test, const Vector3d& axis,
                                               const Vector3d& start, double period) {
  const Vector3d b1 = start.normalized(), b2 = axis.normalized().cross(b1);
  auto direction = [&](double psi) { return Vector3d(std::cos(psi) * b1 + std::sin(psi) * b2); };
  const int steps = std::max(1, int(std::ceil(period / kScanStep - 1e-9)));
  std::vector<std::size_t> missed(steps);
  for (int k = 0; k < steps; ++k)
    missed[k] = test.misses(half_turn(direction(k * kScanStep)), kScanPoints, kScanMisses);

  // The best step of each run of passing steps, the runs with the fewest misses first.
  std::vector<std::pair<std::size_t, int>> seeds;
  for (int k = 0; k < steps;) {
    if (missed[k] > kScanMisses) {
      ++k;
      continue;
    }
    int best = k;
    for (; k < steps && missed[k] <= kScanMisses; ++k)
      if (missed[k] < missed[best]) best = k;
    seeds.push_back({missed[best], best});
  }
  std::sort(seeds.begin(), seeds.end());
  if (seeds.size() > kMaxRuns) seeds.resize(kMaxRuns);

  std::vector<Matrix3d> found;
  for (const auto& [unused, k] : seeds) {
    double best_psi = k * kScanStep, best_score = 1e300;
    for (int j = -kRefineSteps; j <= kRefineSteps; ++j) {
      const double psi = (k + double(j) / kRefineSteps) * kScanStep;
      const double score = test.mean_plane_distance(half_turn(direction(psi)), kRefinePoints);
      if (score < best_score) best_score = score, best_psi = psi;
    }
    const Matrix3d H = half_turn(canonical(direction(best_psi)));
    if (test.accepts(H)) found.push_back(H);
  }
  return found;
}

// Up to `count` directions of the largest total face area and up to `count` directions to the
// vertices farthest from the centre: where the symmetry axes of a part with equal moments lie
// (face centres, vertices). Directions are merged on a grid of about 0.6 degrees.
std::vector<Vector3d> feature_axes(const Mesh& mesh, const Vector3d& centre, std::size_t count) {
  using Key = std::array<long, 3>;
  auto key = [](const Vector3d& v) {
    const Vector3d u = canonical(v.normalized()) * 100;
    return Key{std::lround(u.x()), std::lround(u.y()), std::lround(u.z())};
  };
  std::vector<Vector3d> axes;
  std::map<Key, std::pair<double, Vector3d>> faces;  // area, area-weighted normal
  for (const auto& t : mesh.triangles) {
    const Vector3d a = mesh.positions[t[0]].cast<double>(), b = mesh.positions[t[1]].cast<double>(),
                   c = mesh.positions[t[2]].cast<double>();
    Vector3d n = (b - a).cross(c - a);
    if (!(n.norm() > 0)) continue;
    n = canonical(n);
    auto& f = faces.try_emplace(key(n), 0.0, Vector3d::Zero()).first->second;
    f.first += n.norm();
    f.second += n;
  }
  std::vector<std::tuple<double, Key, Vector3d>> by_area;
  for (const auto& [k, f] : faces) by_area.push_back({-f.first, k, f.second.normalized()});
  std::sort(by_area.begin(), by_area.end(), [](const auto& x, const auto& y) {
    return std::tie(std::get<0>(x), std::get<1>(x)) < std::tie(std::get<0>(y), std::get<1>(y));
  });
  for (std::size_t i = 0; i < std::min(count, by_area.size()); ++i)
    axes.push_back(std::get<2>(by_area[i]));

  std::vector<std::pair<double, std::size_t>> far;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    far.push_back({-(mesh.positions[i].cast<double>() - centre).norm(), i});
  std::sort(far.begin(), far.end());
  std::vector<Vector3d> vertices;
  for (const auto& [minus_r, i] : far) {
    if (vertices.size() == count || -minus_r < 0.99 * -far.front().first || minus_r == 0) break;
    const Vector3d v = mesh.positions[i].cast<double>() - centre;
    if (std::none_of(vertices.begin(), vertices.end(),
                     [&](const Vector3d& w) { return same_axis(v, w); }))
      vertices.push_back(canonical(v.normalized()));
  }
  axes.insert(axes.end(), vertices.begin(), vertices.end());
  return axes;
}

// The group the generators generate (products within kSameRotationDeg merged, the first kept),
// in breadth-first order from the identity; at most `cap` elements.
std::vector<Matrix3d> closure(const std::vector<Matrix3d>& generators, std::size_t cap) {
  std::vector<Matrix3d> group{Matrix3d::Identity()};
  for (std::size_t i = 0; i < group.size(); ++i)
    for (const Matrix3d& g : generators) {
      const Matrix3d p = Eigen::Quaterniond(group[i] * g).normalized().toRotationMatrix();
      if (std::any_of(group.begin(), group.end(), [&](const Matrix3d& e) {
            return rotation_distance_deg(e, p) < kSameRotationDeg;
          }))
        continue;
      if (group.size() == cap) return group;
      group.push_back(p);
    }
  return group;
}

Eigen::Matrix4d about_centre(const Matrix3d& R, const Vector3d& centre) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = R;
  m.topRightCorner<3, 1>() = centre - R * centre;
  return m;
}

}  // namespace

PartSymmetries find_symmetries(const Mesh& mesh) {
  const double area = surface_area(mesh);  // checks the indices and the vertices
  if (!(area > 0)) throw InputError("symmetry search: the mesh has no surface");
  const double diameter = exact_diameter(mesh.positions);
  if (!(diameter > 0 && std::isfinite(diameter)))
    throw InputError("symmetry search: the mesh has no extent");
  const Moments moments = surface_moments(mesh);
  const Vector3d& c = moments.centroid;
  const SurfaceTest test(mesh, c, diameter, area);

  // Ascending moments; e.col(k) the principal axes.
  const Eigen::SelfAdjointEigenSolver<Matrix3d> eig(moments.covariance);
  const Vector3d lambda = eig.eigenvalues();
  Matrix3d e = eig.eigenvectors();
  for (int k = 0; k < 3; ++k) e.col(k) = canonical(e.col(k));
  const double scale = std::max(lambda[2], 1e-300);
  const bool low_equal = lambda[1] - lambda[0] < kEqualMoments * scale;
  const bool high_equal = lambda[2] - lambda[1] < kEqualMoments * scale;

  // Candidate axes; for each, whether the two moments about the axes perpendicular to it are
  // equal (the half turns about those axes must then be scanned for).
  struct Candidate {
    Vector3d axis;
    bool plane_equal;
  };
  std::vector<Candidate> candidates;
  auto add = [&](const Vector3d& a, bool plane_equal) {
    for (const auto& k : candidates)
      if (same_axis(k.axis, a)) return;
    candidates.push_back({canonical(a.normalized()), plane_equal});
  };
  if (low_equal && high_equal) {
    for (int k = 0; k < 3; ++k) add(e.col(k), true);
    for (const Vector3d& a : feature_axes(mesh, c, kFeatureAxes)) add(a, true);
  } else if (low_equal && !high_equal) {
    add(e.col(2), true);  // the other two: arbitrary, only half turns, found by the scan
  } else if (high_equal && !low_equal) {
    add(e.col(0), true);
  } else {
    for (int k = 0; k < 3; ++k) add(e.col(k), false);
  }

  std::vector<AxisResult> results;
  for (const auto& k : candidates) results.push_back(examine_axis(test, k.axis));

  PartSymmetries out;
  std::vector<Vector3d> round;
  for (const auto& r : results)
    if (r.continuous && std::none_of(round.begin(), round.end(),
                                     [&](const Vector3d& a) { return same_axis(a, r.axis); }))
      round.push_back(r.axis);
  if (round.size() >= 2) {  // a sphere: every rotation; two axes say so (BOP, eval)
    for (std::size_t k = 0; k < 2; ++k) out.continuous.push_back({round[k], c});
    return out;
  }
  if (round.size() == 1) {
    out.continuous.push_back({round[0], c});
    const Matrix3d flip = half_turn(perpendicular(round[0]));
    if (test.accepts(flip)) out.discrete.push_back(about_centre(flip, c));
    return out;
  }

  // Discrete: the rotations about the axes found, then the perpendicular half turns.
  std::vector<Matrix3d> generators;
  for (const auto& r : results)
    if (r.order >= 2) generators.push_back(rotation(r.axis, 2 * std::numbers::pi / r.order));
  for (std::size_t i = 0; i < results.size(); ++i) {
    const AxisResult& r = results[i];
    // With distinct moments about the perpendicular axes, these are principal axes, tested
    // above; an axis of order 3 or more makes them equal, whatever the rounding says.
    if (r.order < 3 && !candidates[i].plane_equal) continue;
    Vector3d start = perpendicular(r.axis);
    for (int k = 0; k < 3; ++k)
      if (std::fabs(e.col(k).dot(r.axis)) < 0.5) {
        start = (e.col(k) - e.col(k).dot(r.axis) * r.axis).normalized();
        break;
      }
    for (const Matrix3d& H :
         perpendicular_half_turns(test, r.axis, start, std::numbers::pi / r.order))
      generators.push_back(H);
  }
  const std::vector<Matrix3d> group = closure(generators, kMaxFoundSymmetries);
  for (std::size_t i = 1; i < group.size(); ++i)
    if (test.accepts(group[i])) out.discrete.push_back(about_centre(group[i], c));
  return out;
}

}  // namespace binpick
