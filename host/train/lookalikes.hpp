// Look-alikes of a part: rotations that map most of its surface onto itself, but not all of
// it. A plate's rectangular outline looks the same after a half turn about any of its three axes;
// only its holes tell the four poses apart. Voting sees mostly the outline and faces, so it often
// returns one of the look-alike poses; detection therefore also refines and verifies each
// candidate's look-alikes, and the verified score (which sees the holes against the depth image)
// picks among them (docs/detect/refine.md, "Look-alikes").
//
// Found on the model's subsampled points: rotations about the principal axes of the points
// through the centre of their box in the principal frame by 2 pi k / n (n = 2, 3, 4, 6) under which at least kLookalikeMatchRatio of
// the points land within a voxel of a model point facing the same way (within 30 degrees).
// Rotations that are exact symmetries (the model's own, or about its continuous axis) are left
// out: clustering already treats them as one pose.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "host/core/mesh.hpp"
#include "host/core/symmetry.hpp"

namespace binpick {

inline constexpr double kLookalikeMatchRatio = 0.75;
inline constexpr std::size_t kMaxLookalikes = 8;

// Model-frame rigid transforms x -> S x (rotations about the points' box centre), in a fixed order;
// at most kMaxLookalikes. Empty for a cloud of fewer than 10 points or without normals.
std::vector<Eigen::Isometry3d> find_lookalikes(const PointCloud& model, float voxel_size,
                                                    const PartSymmetries& exact);

}  // namespace binpick
