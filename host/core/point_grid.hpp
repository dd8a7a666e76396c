// A uniform grid over a cloud's points for fixed-radius neighbour queries (cloud normals and
// highest points, scene_cloud.cpp; flat regions, flat_region.cpp).
#pragma once

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "host/core/mesh.hpp"
#include "kernels/scene_shared.h"

namespace binpick {

// A uniform grid of cell `cell` over 2 (x, y) or 3 dimensions: the neighbours of a point within
// `cell` lie in the 3^D cells around its own.
class PointGrid {
 public:
  PointGrid(const PointCloud& cloud, float cell, int dims) : cloud_(cloud), cell_(cell), dims_(dims) {
    for (std::uint32_t i = 0; i < cloud.points.size(); ++i)
      cells_[key(coords(cloud.points[i]))].push_back(i);
  }

  // Calls f(j) for every point j within radius (<= cell) of p, in the grid's (deterministic) order.
  template <class F>
  void near(const Eigen::Vector3f& p, float radius, F&& f) const {
    const Eigen::Vector3i c = coords(p);
    const float r2 = radius * radius;
    for (int dz = (dims_ == 3 ? -1 : 0); dz <= (dims_ == 3 ? 1 : 0); ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          auto it = cells_.find(key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (std::uint32_t j : it->second) {
            const Eigen::Vector3f& q = cloud_.points[j];
            const float d2 = dims_ == 3 ? bp_dist2(p.x(), p.y(), p.z(), q.x(), q.y(), q.z())
                                        : bp_dist2(p.x(), p.y(), 0.0f, q.x(), q.y(), 0.0f);
            if (d2 <= r2) f(j);
          }
        }
  }

 private:
  Eigen::Vector3i coords(const Eigen::Vector3f& p) const {
    const Eigen::Vector3f s = p / cell_;
    return {int(std::floor(s.x())), int(std::floor(s.y())), dims_ == 3 ? int(std::floor(s.z())) : 0};
  }
  static std::int64_t key(const Eigen::Vector3i& c) {
    // 21 bits a coordinate: cells of >= 1e-3 mm over +-1 km (checked by the callers' radius).
    auto b = [](int v) { return std::int64_t(v & 0x1FFFFF); };
    return (b(c.x()) << 42) | (b(c.y()) << 21) | b(c.z());
  }

  const PointCloud& cloud_;
  float cell_;
  int dims_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace binpick
