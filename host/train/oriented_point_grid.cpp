#include "host/train/oriented_point_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick {

OrientedPointGrid::OrientedPointGrid(const PointCloud& cloud, float radius, float min_cos)
    : radius_(radius), min_cos_(min_cos) {
  if (!(radius > 0 && std::isfinite(radius)))
    throw InputError(fmt::format("point grid: radius {} mm must be positive", radius));
  if (cloud.normals.size() != cloud.points.size())
    throw InputError("point grid: every point needs a normal");
  const std::size_t n = cloud.points.size();
  lo_ = Eigen::Vector3f::Zero();
  Eigen::Vector3f hi = Eigen::Vector3f::Zero();
  if (n > 0) {
    lo_ = hi = cloud.points[0];
    for (const auto& p : cloud.points) {
      if (!p.allFinite()) throw InputError("point grid: a point is not finite");
      lo_ = lo_.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  double cells = 1;
  for (int k = 0; k < 3; ++k) {
    dims_[k] = std::int64_t(std::floor((hi[k] - lo_[k]) / radius)) + 1;
    cells *= double(dims_[k]);
  }
  if (cells > double(kMaxCells))
    throw InputError(
        fmt::format("point grid: {:.0f} cells of {} mm, at most {}", cells, radius, kMaxCells));
  auto cell_of = [&](const Eigen::Vector3f& p) {
    std::int64_t c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp<std::int64_t>(std::int64_t(std::floor((p[k] - lo_[k]) / radius)), 0,
                                      dims_[k] - 1);
    return std::size_t((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
  };
  cell_start_.assign(std::size_t(cells) + 1, 0);
  std::vector<std::size_t> cell(n);
  for (std::size_t i = 0; i < n; ++i) ++cell_start_[(cell[i] = cell_of(cloud.points[i])) + 1];
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  std::vector<std::uint32_t> next(cell_start_.begin(), cell_start_.end() - 1);
  points_.resize(n);
  normals_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t at = next[cell[i]]++;
    points_[at] = cloud.points[i];
    normals_[at] = cloud.normals[i];
  }
}

template <class Visit>
bool OrientedPointGrid::visit_near(const Eigen::Vector3f& p, bool centre_first, Visit&& visit) const {
  if (points_.empty() || !p.allFinite()) return false;
  std::int64_t lo[3], hi[3], at[3];
  for (int k = 0; k < 3; ++k) {
    const float f = std::floor((p[k] - lo_[k]) / radius_);
    if (!(f >= -1.0f && f <= float(dims_[k]))) return false;  // every cell within reach is outside
    at[k] = std::int64_t(f);
    lo[k] = std::max<std::int64_t>(at[k] - 1, 0);
    hi[k] = std::min<std::int64_t>(at[k] + 1, dims_[k] - 1);
  }
  const auto cell = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    return std::size_t((z * dims_[1] + y) * dims_[0] + x);
  };
  // p's own cell holds the nearest points more often than not: a search for any match that
  // starts there mostly ends there.
  bool inside = true;
  for (int k = 0; k < 3; ++k) inside = inside && at[k] >= 0 && at[k] < dims_[k];
  const std::size_t own = inside && centre_first ? cell(at[0], at[1], at[2]) : std::size_t(-1);
  if (own != std::size_t(-1))
    for (std::uint32_t i = cell_start_[own]; i < cell_start_[own + 1]; ++i)
      if (visit(i)) return true;
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
      const std::size_t row = cell(0, y, z);
      for (std::uint32_t i = cell_start_[row + lo[0]]; i < cell_start_[row + hi[0] + 1]; ++i)
        if ((own == std::size_t(-1) || i < cell_start_[own] || i >= cell_start_[own + 1]) && visit(i))
          return true;
    }
  return false;
}

bool OrientedPointGrid::matches(const Eigen::Vector3f& p, const Eigen::Vector3f& n) const {
  const float r2 = radius_ * radius_;
  return visit_near(p, true, [&](std::uint32_t i) {
    return (points_[i] - p).squaredNorm() <= r2 && normals_[i].dot(n) >= min_cos_;
  });
}

float OrientedPointGrid::plane_distance(const Eigen::Vector3f& p, const Eigen::Vector3f& n) const {
  float best2 = radius_ * radius_;
  std::uint32_t best = std::numeric_limits<std::uint32_t>::max();
  visit_near(p, false, [&](std::uint32_t i) {
    const float d2 = (points_[i] - p).squaredNorm();
    // Ties go to the first point visited, so the answer does not depend on the scan's end.
    const bool nearer =
        best == std::numeric_limits<std::uint32_t>::max() ? d2 <= best2 : d2 < best2;
    if (nearer && normals_[i].dot(n) >= min_cos_) {
      best2 = d2;
      best = i;
    }
    return false;
  });
  if (best == std::numeric_limits<std::uint32_t>::max()) return radius_;
  return std::min(radius_, std::fabs(normals_[best].dot(p - points_[best])));
}

}  // namespace binpick
