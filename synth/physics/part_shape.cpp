#include "synth/physics/part_shape.hpp"

#include <algorithm>
#include <cmath>

#include "host/core/error.hpp"
#include "synth/physics/bullet_units.hpp"

namespace binpick {

PartShape::PartShape(const ConvexParts& hulls, const MassProperties& mass)
    : inertia_per_mass_(to_units(mass.inertia_per_mass) / btScalar(kMmPerUnit)),
      body_in_part_(mass.principal_frame) {
  if (hulls.hulls.empty()) throw InputError("no convex hulls to simulate");
  const Eigen::Isometry3d part_in_body = body_in_part_.inverse();
  thinnest_mm_ = INFINITY;
  for (const auto& hull : hulls.hulls) {
    thinnest_mm_ = std::min(thinnest_mm_, thinnest_extent(hull));
    auto shape = std::make_unique<btConvexHullShape>();
    for (const auto& v : hull.vertices) {
      const Eigen::Vector3d in_body = part_in_body * v.cast<double>();
      shape->addPoint(to_units(in_body), false);
      bounding_radius_mm_ = std::max(bounding_radius_mm_, in_body.norm());
    }
    shape->recalcLocalAabb();
    shape->setMargin(kMargin);
    // Faces and edges let Bullet clip whole contact patches (several points per pair at
    // once) instead of collecting one GJK point per step: resting piles jitter far less and
    // settle in fewer steps, which more than pays for the clipping.
    shape->initializePolyhedralFeatures();
    hulls_.push_back(std::move(shape));
  }
  bounding_radius_mm_ += kMargin * kMmPerUnit;

  if (hulls_.size() == 1) {
    shape_ = hulls_.front().get();  // a compound of one would only add a tree walk per pair
    return;
  }
  compound_ = std::make_unique<btCompoundShape>(true, static_cast<int>(hulls_.size()));
  for (const auto& hull : hulls_) compound_->addChildShape(btTransform::getIdentity(), hull.get());
  shape_ = compound_.get();
}

}  // namespace binpick
