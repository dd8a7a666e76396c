#include "synth/physics/settle_drift.hpp"

#include <algorithm>
#include <cmath>

#include "synth/physics/bin_world.hpp"
#include "synth/physics/bullet_units.hpp"
#include "synth/physics/mass_properties.hpp"
#include "synth/physics/part_shape.hpp"

namespace binpick {

SettleDrift settle_drift(const ConvexParts& hulls, const Mesh& part, const DropOptions& options,
                         const std::vector<Eigen::Isometry3d>& poses, double seconds) {
  const PartShape shape(hulls, mass_properties(part));
  BinWorld world(options, shape);
  for (const auto& pose : poses) world.add_part(to_units(pose * shape.body_in_part()));
  for (double t = 0; t < seconds;) t += world.step();

  SettleDrift drift;
  drift.parts = static_cast<int>(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Isometry3d before = poses[i] * shape.body_in_part();
    const Eigen::Isometry3d now = to_mm(world.parts()[i]->getWorldTransform());
    const double moved = (now.translation() - before.translation()).norm();
    const double turned = Eigen::AngleAxisd(now.linear().transpose() * before.linear()).angle();
    drift.moved_mm.push_back(moved);
    drift.moved_over_1mm += moved > 1.0;
    drift.moved_over_5mm += moved > 5.0;
    drift.worst_mm = std::max(drift.worst_mm, moved);
    drift.worst_degrees = std::max(drift.worst_degrees, turned * 180.0 / M_PI);
  }
  return drift;
}

}  // namespace binpick
