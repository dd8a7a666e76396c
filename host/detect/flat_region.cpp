#include "host/detect/flat_region.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace binpick {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Cells of 2^20 a side: clouds here span far fewer cells than that.
long long cell_key(const Eigen::Vector3f& p, float cell) {
  const auto c = [&](float v) { return (long long)std::floor(v / cell) & 0xFFFFF; };
  return (c(p.x()) << 40) | (c(p.y()) << 20) | c(p.z());
}

}  // namespace

FlatRegions::FlatRegions(const PointCloud& cloud, const FlatRegionOptions& opt)
    : cloud_(cloud), opt_(opt), cos_angle_(float(std::cos(opt.max_angle * kPi / 180))) {
  const std::size_t n = cloud.points.size();
  std::vector<long long> key(n);
  for (std::size_t i = 0; i < n; ++i) key[i] = cell_key(cloud.points[i], opt_.link);
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
  std::vector<long long> sorted(n);
  for (std::size_t i = 0; i < n; ++i) sorted[i] = key[order[i]];
  const float link2 = opt_.link * opt_.link;
  first_.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const Eigen::Vector3f q = p + opt_.link * Eigen::Vector3f(float(dx), float(dy), float(dz));
          const auto [lo, hi] = std::equal_range(sorted.begin(), sorted.end(), cell_key(q, opt_.link));
          for (auto it = lo; it != hi; ++it) {
            const std::uint32_t j = order[std::size_t(it - sorted.begin())];
            if (j != i && (cloud.points[j] - p).squaredNorm() <= link2) neighbours_.push_back(j);
          }
        }
    first_[i + 1] = std::uint32_t(neighbours_.size());
  }
  stamp_.assign(n, 0);
}

std::size_t FlatRegions::size_from(std::size_t seed) const {
  if (++round_ == 0) {  // the stamps wrapped: start them again
    std::fill(stamp_.begin(), stamp_.end(), 0);
    round_ = 1;
  }
  const Eigen::Vector3f origin = cloud_.points[seed];
  const Eigen::Vector3f normal = cloud_.normals[seed];
  const float r2 = opt_.radius * opt_.radius;
  std::vector<std::uint32_t> front{std::uint32_t(seed)};
  stamp_[seed] = round_;
  std::size_t count = 0;
  while (!front.empty()) {
    const std::uint32_t i = front.back();
    front.pop_back();
    ++count;
    for (std::uint32_t e = first_[i]; e < first_[i + 1]; ++e) {
      const std::uint32_t j = neighbours_[e];
      if (stamp_[j] == round_) continue;
      const Eigen::Vector3f x = cloud_.points[j] - origin;
      if (x.squaredNorm() > r2 || std::abs(normal.dot(x)) > opt_.tolerance ||
          normal.dot(cloud_.normals[j]) < cos_angle_)
        continue;
      stamp_[j] = round_;
      front.push_back(j);
    }
  }
  return count;
}

std::size_t FlatRegions::largest() const {
  std::size_t best = 0;
  for (std::size_t i = 0; i < cloud_.points.size(); ++i) best = std::max(best, size_from(i));
  return best;
}

std::size_t nearest_point(const PointCloud& cloud, const Eigen::Vector3f& p) {
  std::size_t best = 0;
  float d = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const float e = (cloud.points[i] - p).squaredNorm();
    if (e < d) {
      d = e;
      best = i;
    }
  }
  return best;
}

}  // namespace binpick
