// Bullet runs in the paper's units, 1 unit = 1 cm: with a bin in metres and 6 cm parts piles
// never settled, Bullet wants moving objects of at least about 0.2 units (docs/synthesis.md).
// Everything outside synth/physics is in mm.
#pragma once

#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace binpick {

inline constexpr double kMmPerUnit = 10.0;
inline constexpr double kGravityUnits = 981.0;  // cm / s^2

inline btVector3 to_units(const Eigen::Vector3d& mm) {
  return btVector3(btScalar(mm.x() / kMmPerUnit), btScalar(mm.y() / kMmPerUnit),
                   btScalar(mm.z() / kMmPerUnit));
}

inline Eigen::Vector3d to_mm(const btVector3& units) {
  return Eigen::Vector3d(units.x(), units.y(), units.z()) * kMmPerUnit;
}

inline btTransform to_units(const Eigen::Isometry3d& mm) {
  const Eigen::Matrix3d& r = mm.linear();
  const btMatrix3x3 basis(btScalar(r(0, 0)), btScalar(r(0, 1)), btScalar(r(0, 2)),
                          btScalar(r(1, 0)), btScalar(r(1, 1)), btScalar(r(1, 2)),
                          btScalar(r(2, 0)), btScalar(r(2, 1)), btScalar(r(2, 2)));
  return btTransform(basis, to_units(Eigen::Vector3d(mm.translation())));
}

// Through a normalised quaternion in double: Bullet's float basis is orthonormal only to about
// 1e-7, and a pose written to a dataset should be a rotation to double precision.
inline Eigen::Isometry3d to_mm(const btTransform& units) {
  const btQuaternion q = units.getRotation();
  Eigen::Isometry3d mm = Eigen::Isometry3d::Identity();
  mm.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
  mm.translation() = to_mm(units.getOrigin());
  return mm;
}

}  // namespace binpick
