// Known symmetries of a part, in the BOP models_info.json convention, so evaluation can treat
// symmetric poses as equal.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace binpick {

// Two rotations within this many degrees of each other are one (symmetry detection's group,
// look-alikes against the exact ones).
inline constexpr double kSameRotationDeg = 5.0;

// The part is unchanged by any rotation about this axis through this point (mm).
struct ContinuousSymmetry {
  Eigen::Vector3d axis;
  Eigen::Vector3d offset;
};

struct PartSymmetries {
  std::vector<ContinuousSymmetry> continuous;
  // Rigid transforms (not the identity) that map the part onto itself; translation in mm.
  std::vector<Eigen::Matrix4d> discrete;

  bool empty() const { return continuous.empty() && discrete.empty(); }

  // The symmetries of the part scaled by factor about the origin.
  PartSymmetries scaled(double factor) const {
    PartSymmetries result = *this;
    for (auto& s : result.continuous) s.offset *= factor;
    for (auto& m : result.discrete) m.block<3, 1>(0, 3) *= factor;
    return result;
  }
};

}  // namespace binpick
