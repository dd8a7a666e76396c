#include "host/detect/verify/rival.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "host/core/two_halves.hpp"

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
    : cam_(cam), band_(2 * spacing) {
  if (points.size() != normals.size() || !(spacing > 0))
    throw std::logic_error("posed surface: a normal per point and a spacing > 0 expected");
  const Eigen::Matrix3f Rf = R.cast<float>();
  const Eigen::Vector3f tf = t.cast<float>();
  Eigen::Vector2f lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  // Only points near the image go into the grid: no disc of one farther out reaches a pixel
  // of the image, where every measured point lies, and a pose with points just in front of the
  // camera projects them millions of pixels out (a window that large would not fit in memory).
  const float margin = float(kMaxRadius + 1);
  const auto near_image = [&](const Eigen::Vector2f& uv) {
    return uv.x() >= -margin && uv.y() >= -margin && uv.x() <= float(cam.width) + margin &&
           uv.y() <= float(cam.height) + margin;
  };
  double depth = 0;
  for (std::size_t j = 0; j < points.size(); ++j) {
    const Eigen::Vector3f q = Rf * points[j] + tf;
    const Eigen::Vector3f nq = Rf * normals[j];
    if (!(q.z() > 0) || -nq.dot(q) < kMinCos * q.norm() * nq.norm()) continue;
    const Eigen::Vector2f uv(cam.fx * q.x() / q.z() + cam.cx, cam.fy * q.y() / q.z() + cam.cy);
    if (!uv.allFinite()) continue;
    q_.push_back(q);
    nq_.push_back(nq.normalized());
    pixel_.push_back(uv);
    if (near_image(uv)) lo = lo.cwiseMin(uv), hi = hi.cwiseMax(uv);
    depth += q.z();
  }
  if (q_.empty() || !(lo.x() <= hi.x())) return;  // no grid: no point stands for any pixel
  depth /= double(q_.size());
  // A model point stands for the pixels within 0.75 of the points' spacing of it: a pixel of
  // the model's surface has a point that near (points a spacing apart leave none farther than
  // about 0.71 of it).
  radius_ = std::clamp(int(std::ceil(0.75 * spacing * cam.fx / depth)), 1, kMaxRadius);
  // Square cells a radius wide: the points that may stand for a pixel lie in the 3 x 3 cells
  // around its own. Counting sort keeps each cell's points in index order.
  u0_ = int(std::floor(lo.x())) - radius_;
  v0_ = int(std::floor(lo.y())) - radius_;
  cells_u_ = (int(std::floor(hi.x())) + radius_ + 1 - u0_) / radius_ + 1;
  cells_v_ = (int(std::floor(hi.y())) + radius_ + 1 - v0_) / radius_ + 1;
  std::vector<std::uint32_t> cell_of(q_.size());
  cell_start_.assign(std::size_t(cells_u_) * std::size_t(cells_v_) + 1, 0);
  constexpr std::uint32_t kNoCell = 0xffffffffu;
  for (std::size_t j = 0; j < q_.size(); ++j) {
    cell_of[j] = kNoCell;
    if (!near_image(pixel_[j])) continue;
    const int cu = int(std::floor(pixel_[j].x() + 0.5f));
    const int cv = int(std::floor(pixel_[j].y() + 0.5f));
    cell_of[j] = std::uint32_t((cv - v0_) / radius_) * std::uint32_t(cells_u_) +
                 std::uint32_t((cu - u0_) / radius_);
    ++cell_start_[cell_of[j] + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_points_.resize(cell_start_.back());
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t j = 0; j < q_.size(); ++j)
    if (cell_of[j] != kNoCell) cell_points_[fill[cell_of[j]]++] = std::uint32_t(j);
}

std::int32_t PosedSurface::nearest(int u, int v) const {
  // The points within the radius of the pixel, in index order; of them the nearest in the
  // image, but a point nearer the camera by more than twice the spacing wins (the near side of
  // the part hides its far side), taken in index order like a splat of each point's disc.
  // Few points cover a pixel (about two on a surface sampled at the spacing); a pile of them
  // (a model sampled far finer than its spacing says) spills to the heap.
  constexpr std::size_t kOnStack = 32;
  struct Candidate {
    std::uint32_t j;
    float d2;  // squared image distance to the pixel
  };
  std::array<Candidate, kOnStack> on_stack{};
  std::vector<Candidate> spilled;
  std::size_t n = 0;
  const float r2 = float(radius_ * radius_);
  const int gu = (u - u0_) / radius_, gv = (v - v0_) / radius_;
  for (int cv = std::max(gv - 1, 0); cv <= std::min(gv + 1, cells_v_ - 1); ++cv)
    for (int cu = std::max(gu - 1, 0); cu <= std::min(gu + 1, cells_u_ - 1); ++cu) {
      const std::size_t c = std::size_t(cv) * std::size_t(cells_u_) + std::size_t(cu);
      for (std::uint32_t i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
        const std::uint32_t j = cell_points_[i];
        const float d2 = (Eigen::Vector2f(float(u), float(v)) - pixel_[j]).squaredNorm();
        if (d2 > r2) continue;
        if (n == kOnStack) spilled.assign(on_stack.begin(), on_stack.end());
        if (n >= kOnStack) spilled.push_back({j, d2});
        else on_stack[n] = {j, d2};
        ++n;
      }
    }
  Candidate* const found = n > kOnStack ? spilled.data() : on_stack.data();
  std::sort(found, found + n, [](const Candidate& a, const Candidate& b) { return a.j < b.j; });
  std::int32_t best_j = -1;
  float best = INFINITY;
  for (std::size_t i = 0; i < n; ++i) {
    const auto [j, d2] = found[i];
    const bool nearer = best_j < 0 || q_[j].z() < q_[std::size_t(best_j)].z() - band_ ||
                        (q_[j].z() <= q_[std::size_t(best_j)].z() + band_ && d2 < best);
    if (nearer) {
      best_j = std::int32_t(j);
      best = d2;
    }
  }
  return best_j;
}

double PosedSurface::along_ray(const Eigen::Vector3f& m) const {
  if (q_.empty() || !(m.z() > 0)) return kNaN;
  const float fu = std::floor(cam_.fx * m.x() / m.z() + cam_.cx + 0.5f);
  const float fv = std::floor(cam_.fy * m.y() / m.z() + cam_.cy + 0.5f);
  // Outside the window of the points' discs (or not a number): no point stands for the pixel.
  const float width = float(cells_u_ * radius_), height = float(cells_v_ * radius_);
  if (!(fu >= float(u0_) && fv >= float(v0_) && fu < float(u0_) + width &&
        fv < float(v0_) + height))
    return kNaN;
  const std::int32_t j = nearest(int(fu), int(fv));
  if (j < 0) return kNaN;
  const Eigen::Vector3f& q = q_[std::size_t(j)];
  const Eigen::Vector3f& n = nq_[std::size_t(j)];
  const float c = -n.dot(m.normalized());
  return double(n.dot(m - q) / std::max(c, kMinCos));
}

std::vector<double> own_residuals(const PosedSurface& surface,
                                  std::span<const Eigen::Vector3f> measured) {
  std::vector<double> out(measured.size());
  for (std::size_t k = 0; k < measured.size(); ++k) out[k] = surface.along_ray(measured[k]);
  return out;
}

RivalComparison compare_rivals(const PosedSurface& a, std::span<const Eigen::Vector3f> measured_a,
                               std::span<const double> own_a, const PosedSurface& b,
                               std::span<const Eigen::Vector3f> measured_b,
                               std::span<const double> own_b, double tolerance,
                               bool count_unexplained, double min_shared) {
  if (own_a.size() != measured_a.size() || own_b.size() != measured_b.size())
    throw std::logic_error("compare rivals: one own residual per measured point expected");
  RivalComparison c;
  const std::size_t total = measured_a.size() + measured_b.size();
  const double cap = tolerance * tolerance;
  double sum_a = 0, sum_b = 0, sum_d = 0, sum_d2 = 0;
  const auto add = [&](double ea, double eb) {
    ++c.union_size;
    const bool both = std::isfinite(ea) && std::isfinite(eb);
    if (both) ++c.shared;
    if (!both && !count_unexplained) return;
    // A point one pose has no surface at is left unexplained by it: the clip's cost.
    const double sa = std::isfinite(ea) ? std::min(ea * ea, cap) : cap;
    const double sb = std::isfinite(eb) ? std::min(eb * eb, cap) : cap;
    ++c.compared;
    sum_a += sa;
    sum_b += sb;
    sum_d += sb - sa;
    sum_d2 += (sb - sa) * (sb - sa);
  };
  const auto hopeless = [&] {
    // The most the whole union could share, against the share as cap_by_rivals checks it.
    const std::size_t most = total - (c.union_size - c.shared);
    if (!(double(most) < min_shared * double(total))) return false;
    c.union_size = total;  // the share stays below min_shared, as the whole union's would
    c.compared = 0;
    c.stopped = true;
    return true;
  };
  for (std::size_t k = 0; k < measured_a.size(); ++k) {
    add(own_a[k], b.along_ray(measured_a[k]));
    if (min_shared > 0 && hopeless()) return c;
  }
  for (std::size_t k = 0; k < measured_b.size(); ++k) {
    add(a.along_ray(measured_b[k]), own_b[k]);
    if (min_shared > 0 && hopeless()) return c;
  }
  if (c.compared < 2) return c;
  const double n = double(c.compared);
  c.ms_a = sum_a / n;
  c.ms_b = sum_b / n;
  const double mean = sum_d / n;
  c.standard_error = std::sqrt(std::max(0.0, (sum_d2 - sum_d * mean) / (n - 1)) / n);
  return c;
}

RivalComparison compare_rivals(const PosedSurface& a, std::span<const Eigen::Vector3f> measured_a,
                               const PosedSurface& b, std::span<const Eigen::Vector3f> measured_b,
                               double tolerance, bool count_unexplained) {
  return compare_rivals(a, measured_a, own_residuals(a, measured_a), b, measured_b,
                        own_residuals(b, measured_b), tolerance, count_unexplained);
}

void cap_by_rivals(std::vector<VerifiedPose>& poses, std::span<const Eigen::Vector3f> points,
                std::span<const Eigen::Vector3f> normals, float spacing, const bp_camera& cam,
                const Eigen::Vector3d& centroid, const RivalOptions& opt) {
  if (!(opt.significance > 0)) return;
  const std::size_t n = poses.size();
  std::vector<double> before(n), cap(n, INFINITY);
  for (std::size_t k = 0; k < n; ++k) before[k] = poses[k].score();
  // The pairs to compare, and the surfaces they need.
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  std::vector<std::size_t> needed;
  std::vector<bool> needs(n, false);
  std::vector<Eigen::Vector3d> centre(n);  // posed centroids
  for (std::size_t k = 0; k < n; ++k) centre[k] = poses[k].R * centroid + poses[k].t;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(before[i] > 0) || poses[i].measured.empty()) continue;
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!(before[j] > 0) || poses[j].measured.empty()) continue;
      if (opt.max_centre_distance > 0 && (centre[i] - centre[j]).norm() > opt.max_centre_distance)
        continue;
      pairs.emplace_back(i, j);
      for (const std::size_t k : {i, j})
        if (!needs[k]) needs[k] = true, needed.push_back(k);
    }
  }
  // Surfaces and comparisons are independent: half of each on a second thread.
  std::vector<std::optional<PosedSurface>> surface(n);
  std::vector<std::vector<double>> own(n);
  in_two_halves(needed.size(), [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i) {
      const std::size_t k = needed[i];
      surface[k].emplace(poses[k].R, poses[k].t, points, normals, cam, spacing);
      own[k] = own_residuals(*surface[k], poses[k].measured);
    }
  });
  std::vector<RivalComparison> compared(pairs.size());
  in_two_halves(pairs.size(), [&](std::size_t first, std::size_t last) {
    for (std::size_t p = first; p < last; ++p) {
      const auto [i, j] = pairs[p];
      compared[p] = compare_rivals(*surface[i], poses[i].measured, own[i], *surface[j],
                                   poses[j].measured, own[j], poses[i].evidence.tolerance,
                                   opt.count_unexplained, opt.min_shared);
    }
  });
  const auto out_fits = [&](std::size_t winner, std::size_t loser, double ms_w, double ms_l,
                            std::size_t shared) {
    const double limit = before[winner] * (ms_l > 0 ? ms_w / ms_l : 1.0);
    if (limit < cap[loser]) {
      cap[loser] = limit;
      poses[loser].evidence.rival_shared = std::uint32_t(shared);
      poses[loser].evidence.rival_ms = ms_w;
      poses[loser].evidence.own_ms = ms_l;
    }
  };
  // In pair order, as one thread would: the first of equal caps is kept.
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto [i, j] = pairs[p];
    const RivalComparison& c = compared[p];
    if (c.shared < opt.min_points || double(c.shared) < opt.min_shared * double(c.union_size))
      continue;
    const double margin =
        std::max({opt.significance * c.standard_error, opt.dead_band * std::min(c.ms_a, c.ms_b),
                  opt.dead_band_floor});
    if (c.ms_b - c.ms_a > margin) out_fits(i, j, c.ms_a, c.ms_b, c.shared);
    else if (c.ms_a - c.ms_b > margin) out_fits(j, i, c.ms_b, c.ms_a, c.shared);
  }
  for (std::size_t k = 0; k < n; ++k)
    if (cap[k] < poses[k].score()) poses[k].breakdown[kRivalCap] = cap[k];
}

}  // namespace binpick
