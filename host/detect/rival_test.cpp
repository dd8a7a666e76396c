#include "host/detect/rival_test.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace binpick {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A model point faces the camera at cosines of at least this (pose_fit_shared.h's BP_FIT_MIN_COS).
constexpr float kMinCos = 0.17f;

}  // namespace

std::vector<Eigen::Vector3f> measured_points(std::span<const float> residuals,
                                             const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                                             std::span<const Eigen::Vector3f> points,
                                             std::span<const Eigen::Vector3f> normals,
                                             const bp_camera& cam) {
  if (residuals.size() != points.size() || normals.size() != points.size())
    throw std::logic_error("measured points: one residual and normal per model point expected");
  const Eigen::Matrix3f Rf = R.cast<float>();
  const Eigen::Vector3f tf = t.cast<float>();
  std::vector<Eigen::Vector3f> out;
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (!std::isfinite(residuals[j])) continue;
    // The pixel as the kernel finds it, and the ray through its centre, on which the measured
    // point lies (depth_to_points.cl).
    const Eigen::Vector3f q = Rf * points[j] + tf;
    const Eigen::Vector3f nq = Rf * normals[j];
    if (!(q.z() > 0)) continue;
    const float pu = std::floor(cam.fx * q.x() / q.z() + cam.cx + 0.5f);
    const float pv = std::floor(cam.fy * q.y() / q.z() + cam.cy + 0.5f);
    const Eigen::Vector3f ray((pu - cam.cx) / cam.fx, (pv - cam.cy) / cam.fy, 1.0f);
    const float along = nq.dot(ray);
    if (!(std::abs(along) > 1e-6f)) continue;
    const float z = (residuals[j] + nq.dot(q)) / along;
    if (z > 0 && std::isfinite(z)) out.push_back(z * ray);
  }
  return out;
}

PosedSurface::PosedSurface(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                           std::span<const Eigen::Vector3f> points,
                           std::span<const Eigen::Vector3f> normals, const bp_camera& cam,
                           float spacing)
    : cam_(cam) {
  if (points.size() != normals.size() || !(spacing > 0))
    throw std::logic_error("posed surface: a normal per point and a spacing > 0 expected");
  const Eigen::Matrix3f Rf = R.cast<float>();
  const Eigen::Vector3f tf = t.cast<float>();
  std::vector<Eigen::Vector2f> pixel;
  Eigen::Vector2f lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  double depth = 0;
  for (std::size_t j = 0; j < points.size(); ++j) {
    const Eigen::Vector3f q = Rf * points[j] + tf;
    const Eigen::Vector3f nq = Rf * normals[j];
    if (!(q.z() > 0) || -nq.dot(q) < kMinCos * q.norm() * nq.norm()) continue;
    const Eigen::Vector2f uv(cam.fx * q.x() / q.z() + cam.cx, cam.fy * q.y() / q.z() + cam.cy);
    if (!uv.allFinite()) continue;
    q_.push_back(q);
    nq_.push_back(nq.normalized());
    pixel.push_back(uv);
    lo = lo.cwiseMin(uv);
    hi = hi.cwiseMax(uv);
    depth += q.z();
  }
  if (q_.empty()) return;
  depth /= double(q_.size());
  // A model point stands for the pixels within 0.75 of the points' spacing of it: a pixel of
  // the model's surface has a point that near (points a spacing apart leave none farther than
  // about 0.71 of it).
  radius_ = std::clamp(int(std::ceil(0.75 * spacing * cam.fx / depth)), 1, kMaxRadius);
  u0_ = int(std::floor(lo.x())) - radius_;
  v0_ = int(std::floor(lo.y())) - radius_;
  width_ = int(std::floor(hi.x())) + radius_ + 1 - u0_;
  height_ = int(std::floor(hi.y())) + radius_ + 1 - v0_;
  nearest_.assign(std::size_t(width_) * std::size_t(height_), -1);
  std::vector<float> best(nearest_.size(), INFINITY);
  const float r2 = float(radius_ * radius_);
  const float band = 2 * spacing;
  for (std::size_t j = 0; j < q_.size(); ++j) {
    const int cu = int(std::floor(pixel[j].x() + 0.5f)), cv = int(std::floor(pixel[j].y() + 0.5f));
    for (int v = cv - radius_; v <= cv + radius_; ++v)
      for (int u = cu - radius_; u <= cu + radius_; ++u) {
        const float d2 = (Eigen::Vector2f(float(u), float(v)) - pixel[j]).squaredNorm();
        if (d2 > r2) continue;
        // Nearest in the image, but a point nearer the camera by more than twice the spacing
        // wins (the near side of the part hides its far side).
        const std::size_t k = std::size_t(v - v0_) * std::size_t(width_) + std::size_t(u - u0_);
        const std::int32_t old = nearest_[k];
        const bool nearer = old < 0 || q_[j].z() < q_[std::size_t(old)].z() - band ||
                            (q_[j].z() <= q_[std::size_t(old)].z() + band && d2 < best[k]);
        if (nearer) {
          nearest_[k] = std::int32_t(j);
          best[k] = d2;
        }
      }
  }
}

double PosedSurface::along_ray(const Eigen::Vector3f& m) const {
  if (nearest_.empty() || !(m.z() > 0)) return kNaN;
  const int u = int(std::floor(cam_.fx * m.x() / m.z() + cam_.cx + 0.5f)) - u0_;
  const int v = int(std::floor(cam_.fy * m.y() / m.z() + cam_.cy + 0.5f)) - v0_;
  if (u < 0 || v < 0 || u >= width_ || v >= height_) return kNaN;
  const std::int32_t j = nearest_[std::size_t(v) * std::size_t(width_) + std::size_t(u)];
  if (j < 0) return kNaN;
  const Eigen::Vector3f& q = q_[std::size_t(j)];
  const Eigen::Vector3f& n = nq_[std::size_t(j)];
  const float c = -n.dot(m.normalized());
  return double(n.dot(m - q) / std::max(c, kMinCos));
}

RivalComparison compare_rivals(const PosedSurface& a, std::span<const Eigen::Vector3f> measured_a,
                               const PosedSurface& b, std::span<const Eigen::Vector3f> measured_b,
                               double tolerance, bool count_unexplained) {
  RivalComparison c;
  const double cap = tolerance * tolerance;
  double sum_a = 0, sum_b = 0, sum_d = 0, sum_d2 = 0;
  for (const std::span<const Eigen::Vector3f> measured : {measured_a, measured_b})
    for (const Eigen::Vector3f& m : measured) {
      ++c.union_size;
      const double ea = a.along_ray(m), eb = b.along_ray(m);
      const bool both = std::isfinite(ea) && std::isfinite(eb);
      if (both) ++c.shared;
      if (!both && !count_unexplained) continue;
      // A point one pose has no surface at is left unexplained by it: the clip's cost.
      const double sa = std::isfinite(ea) ? std::min(ea * ea, cap) : cap;
      const double sb = std::isfinite(eb) ? std::min(eb * eb, cap) : cap;
      ++c.compared;
      sum_a += sa;
      sum_b += sb;
      sum_d += sb - sa;
      sum_d2 += (sb - sa) * (sb - sa);
    }
  if (c.compared < 2) return c;
  const double n = double(c.compared);
  c.ms_a = sum_a / n;
  c.ms_b = sum_b / n;
  const double mean = sum_d / n;
  c.standard_error = std::sqrt(std::max(0.0, (sum_d2 - sum_d * mean) / (n - 1)) / n);
  return c;
}

void rival_test(std::vector<RefinedPose>& poses, std::span<const Eigen::Vector3f> points,
                std::span<const Eigen::Vector3f> normals, float spacing, const bp_camera& cam,
                const Eigen::Vector3d& centroid, const RivalTestOptions& opt) {
  if (!(opt.significance > 0)) return;
  const std::size_t n = poses.size();
  // Built when a pose first takes part in a comparison.
  std::vector<std::optional<PosedSurface>> surface(n);
  const auto surface_of = [&](std::size_t k) -> const PosedSurface& {
    if (!surface[k]) surface[k].emplace(poses[k].R, poses[k].t, points, normals, cam, spacing);
    return *surface[k];
  };
  std::vector<double> before(n), cap(n, INFINITY);
  for (std::size_t k = 0; k < n; ++k) before[k] = poses[k].score;
  const auto out_fits = [&](std::size_t winner, std::size_t loser, double ms_w, double ms_l,
                            std::size_t shared) {
    const double limit = before[winner] * (ms_l > 0 ? ms_w / ms_l : 1.0);
    if (limit < cap[loser]) {
      cap[loser] = limit;
      poses[loser].rival_shared = std::uint32_t(shared);
      poses[loser].rival_ms = ms_w;
      poses[loser].own_ms = ms_l;
    }
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!(before[i] > 0) || poses[i].measured.empty()) continue;
    const Eigen::Vector3d ci = poses[i].R * centroid + poses[i].t;
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!(before[j] > 0) || poses[j].measured.empty()) continue;
      const Eigen::Vector3d cj = poses[j].R * centroid + poses[j].t;
      if (opt.max_centre_distance > 0 && (ci - cj).norm() > opt.max_centre_distance) continue;
      const RivalComparison c = compare_rivals(surface_of(i), poses[i].measured, surface_of(j),
                                               poses[j].measured, poses[i].tolerance,
                                               opt.count_unexplained);
      if (c.shared < opt.min_points || double(c.shared) < opt.min_shared * double(c.union_size))
        continue;
      const double margin =
          std::max({opt.significance * c.standard_error, opt.dead_band * std::min(c.ms_a, c.ms_b),
                    opt.dead_band_floor});
      if (c.ms_b - c.ms_a > margin) out_fits(i, j, c.ms_a, c.ms_b, c.shared);
      else if (c.ms_a - c.ms_b > margin) out_fits(j, i, c.ms_b, c.ms_a, c.shared);
    }
  }
  for (std::size_t k = 0; k < n; ++k)
    if (cap[k] < poses[k].score) {
      poses[k].rival_out_fitted = true;
      poses[k].score = std::max(0.0, cap[k]);
    }
}

}  // namespace binpick
