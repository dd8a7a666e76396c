#include "host/detect/hypotheses/flat_region.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "host/core/point_grid.hpp"

namespace binpick {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

FlatRegions::FlatRegions(const PointCloud& cloud, const FlatRegionOptions& opt)
    : cloud_(cloud), opt_(opt), cos_angle_(float(std::cos(opt.max_angle * kPi / 180))) {
  const std::size_t n = cloud.points.size();
  first_.assign(n + 1, 0);
  if (n > 0) {
    const PointGrid grid(cloud, opt_.link, 3);
    for (std::size_t i = 0; i < n; ++i) {
      grid.near(cloud.points[i], opt_.link, [&](std::uint32_t j) {
        if (j != i) neighbours_.push_back(j);
      });
      first_[i + 1] = std::uint32_t(neighbours_.size());
    }
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

FlatRegionSkip::FlatRegionSkip(const PointCloud& model, float diameter, float voxel_size,
                               double ratio, bool thin)
    : model_(model), diameter_(diameter), voxel_size_(voxel_size), ratio_(ratio), thin_(thin) {}

std::string FlatRegionSkip::reason(const PointCloud& sample, const Eigen::Vector3f& point,
                                   double noise, double voxel_factor) const {
  if (ratio_ <= 0 || thin_ || sample.points.empty()) return {};
  const double quarter = 0.25 * voxel_size_;
  const int step = int(std::ceil(std::max(0.5 * voxel_size_, 2 * noise) / quarter));
  FlatRegionOptions o;
  o.radius = 0.5f * diameter_;
  o.tolerance = float(step * quarter);
  o.link = 2.0f * voxel_size_;
  auto found = widest_.find(step);
  if (found == widest_.end()) found = widest_.emplace(step, FlatRegions(model_, o).largest()).first;
  const std::size_t part = found->second;
  // Stretched scene voxels lie further apart along the camera's axis.
  o.link *= float(std::max(1.0, voxel_factor));
  const std::size_t seen = FlatRegions(sample, o).size_from(nearest_point(sample, point));
  if (double(seen) <= ratio_ * double(part)) return {};
  return fmt::format(
      "skipped: the highest point lies on a flat region of {} points, more than {} times the "
      "part's widest ({} points): not the part (--flat-region)",
      seen, ratio_, part);
}

}  // namespace binpick
