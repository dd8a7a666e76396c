// The Bullet collision shape of a part, shared by every body of a bin (one shape, many bodies
// keeps memory and the collision caches small). Bullet puts a body's origin at its centre of
// mass with the inertia diagonal, so the hulls are stored in that principal frame and the
// offset to the part frame is kept to report part poses.
#pragma once

#include <btBulletCollisionCommon.h>

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "synth/decompose/convex_parts.hpp"
#include "synth/physics/mass_properties.hpp"

namespace binpick {

class PartShape {
 public:
  // Bullet's collision margin around every hull, units: its default, 0.4 mm at 1 unit = 1 cm,
  // small next to a part yet enough for GJK to keep resting contacts stable.
  static constexpr btScalar kMargin = btScalar(0.04);

  PartShape(const ConvexParts& hulls, const MassProperties& mass);

  btCollisionShape* shape() const { return shape_; }
  // Principal moments of inertia for a mass of 1 (units^2).
  btVector3 inertia_per_mass() const { return inertia_per_mass_; }
  // part frame <- body (principal) frame, mm.
  const Eigen::Isometry3d& body_in_part() const { return body_in_part_; }
  // Largest distance of a hull vertex from the centre of mass, margin included, mm.
  double bounding_radius_mm() const { return bounding_radius_mm_; }
  // The smallest extent of any hull along its principal axes, mm: a part that moves further
  // than this in one step may pass through another part's thinnest piece unseen.
  double thinnest_mm() const { return thinnest_mm_; }

 private:
  std::vector<std::unique_ptr<btConvexHullShape>> hulls_;
  std::unique_ptr<btCompoundShape> compound_;
  btCollisionShape* shape_ = nullptr;  // the only hull, or the compound of several
  btVector3 inertia_per_mass_;
  Eigen::Isometry3d body_in_part_;
  double bounding_radius_mm_ = 0.0;
  double thinnest_mm_ = 0.0;
};

}  // namespace binpick
