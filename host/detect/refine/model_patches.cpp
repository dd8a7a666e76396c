#include "host/detect/refine/model_patches.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace binpick {

ModelPatches model_patches(const PointCloud& model, float size) {
  if (!(size > 0)) throw std::logic_error("patch size must be positive");
  ModelPatches out;
  if (model.points.empty()) return out;
  out.of_point.reserve(model.points.size());
  // The grid starts at the model's lowest corner, not at its origin: the same part gives the
  // same patches wherever its CAD file puts the origin.
  Eigen::Vector3f low = model.points.front();
  for (const Eigen::Vector3f& p : model.points) low = low.cwiseMin(p);
  std::map<std::tuple<long, long, long>, std::uint32_t> cells;
  for (const Eigen::Vector3f& point : model.points) {
    const Eigen::Vector3f p = (point - low) / size;
    const auto cell = std::make_tuple(long(std::floor(p.x())), long(std::floor(p.y())),
                                      long(std::floor(p.z())));
    const auto [it, added] = cells.emplace(cell, out.count);
    if (added) ++out.count;
    out.of_point.push_back(it->second);
  }
  return out;
}

}  // namespace binpick
