// Pose clustering (Drost 2010; paper section III-B and IV): candidate poses
// within a translation threshold (14.4 % of the diameter) and a rotation threshold (20 degrees)
// are grouped, the group's votes summed and its poses averaged.
//
// The pairwise compatibility matrix and each pose's neighbourhood score (the votes of all poses
// compatible with it) are a kernel (kernels/pose_cluster.cl). The grouping is greedy on the host,
// which is sequential by nature and cheap (n^2 bytes read once): poses in order of score, then
// votes, then index; each pose not yet grouped starts a cluster and takes every ungrouped pose
// compatible with it. Unlike Drost's first-come grouping this centres clusters on the densest
// poses, so a cluster is not split by whichever pose happened to come first. A cluster's pose is
// the vote-weighted mean: translations averaged, quaternions sign-aligned with the centre's,
// summed and normalised (the rotation threshold keeps them close, where this mean is accurate).
//
// A symmetric part has several poses that look the same: poses that differ by one of its
// symmetries are one pose (kernels/pose_cluster_shared.h says how the rotation distance takes
// them into account), so their votes add up instead of splitting into separate clusters. Before
// averaging, each member is replaced by its symmetric equivalent nearest the centre's rotation.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "host/core/symmetry.hpp"
#include "host/runtime/cl/cl_buffer.hpp"
#include "host/detect/vote/ppf_pose.hpp"
#include "kernels/binpick_shared.h"
#include "kernels/pose_cluster_shared.h"

namespace binpick {

struct ClusterOptions {
  float max_distance = 7.5f;  // mm (14.4 % of a 52 mm diameter)
  float max_angle_deg = 20.0f;
  // Model-frame point whose posed positions are compared (cluster_poses): the model's centroid.
  // A CAD origin far from the part would otherwise turn a small rotation difference into a large
  // translation difference and split one pose into several clusters.
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  // The part's symmetries in the model frame (PpfModel::symmetries). Only their rotations
  // matter: each keeps the part's centroid, and so `centre`, in place (up to a model voxel).
  PartSymmetries symmetries = {};
};
// InputError for a bad distance or angle, or symmetries cluster_symmetry refuses.
void check(const ClusterOptions& opt);

// The symmetries as the rotation test takes them (kernels/pose_cluster_shared.h).
struct ClusterSymmetry {
  std::uint32_t mode = BP_CLUSTER_ROTATIONS;
  std::vector<Eigen::Quaternionf> rotations;        // BP_CLUSTER_ROTATIONS: not the identity
  Eigen::Vector3f axis = Eigen::Vector3f::UnitZ();  // axis modes: unit, model frame
  Eigen::Quaterniond flip = Eigen::Quaterniond::Identity();  // AXIS_EITHER: reverses the axis
};

// One continuous axis (several parallel ones count as one): an axis mode, AXIS_EITHER when a
// discrete symmetry reverses the axis; two non-parallel axes: ANY; otherwise the discrete
// rotations (identities dropped). Throws InputError for a zero or non-finite axis, a discrete
// transform whose rotation part is not a rotation, or more than BP_CLUSTER_MAX_SYMMETRIES
// discrete rotations.
ClusterSymmetry cluster_symmetry(const PartSymmetries& symmetries);

struct PoseCompatibility {
  std::size_t n = 0;
  std::vector<std::uint8_t> compatible;  // n * n, row-major, 1 = may be grouped
  std::vector<std::uint32_t> scores;     // n: votes of the poses compatible with each
};

// Largest number of candidates clustered at once (the matrix is n^2 bytes).
inline constexpr std::size_t kMaxClusterPoses = 8192;

// The predicate of the kernel for a part without symmetries, in the same float operations.
bool pose_compatible(const PoseCandidate& a, const PoseCandidate& b, float max_dist2,
                     float min_cos_half);

// Device routine (kernel pose_compatibility). InputError for more than kMaxClusterPoses.
PoseCompatibility pose_compatibility(ocl::Device& dev, const std::vector<PoseCandidate>& poses,
                                     const ClusterOptions& opt);
// Reference: the same matrix and scores in plain C++.
PoseCompatibility pose_compatibility_reference(const std::vector<PoseCandidate>& poses,
                                               const ClusterOptions& opt);

struct PoseCluster {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  // averaged, unit
  Eigen::Vector3d t = Eigen::Vector3d::Zero();            // averaged, mm
  std::uint64_t votes = 0;                                // summed
  std::uint32_t centre = 0;                               // index of the centre pose
  std::vector<std::uint32_t> members;                     // ascending pose indices
};

// The greedy grouping of the comment above; clusters by votes (most first; ties: the order in
// which they were formed). Members are aligned to the centre by `symmetry` before averaging.
std::vector<PoseCluster> group_poses(const std::vector<PoseCandidate>& poses,
                                     const PoseCompatibility& compatibility,
                                     const ClusterSymmetry& symmetry = {});

// Among the rotations q g (g a symmetry of the part, the identity included; for an axis, every
// turn about it), the one nearest `centre`, sign-aligned with it. For ANY: centre.
Eigen::Quaterniond nearest_equivalent(const Eigen::Quaterniond& q, const Eigen::Quaterniond& centre,
                                      const ClusterSymmetry& symmetry);

// Both steps on the poses moved to opt.centre (t + R centre, then back for the clusters' t):
// at most kMaxClusterPoses candidates, the most voted (ties: lower index) if there are more.
// Appends the stage "cluster" to timings if given.
std::vector<PoseCluster> cluster_poses(ocl::Device& dev, const std::vector<PoseCandidate>& poses,
                                       const ClusterOptions& opt,
                                       StageTimings* timings = nullptr);

}  // namespace binpick
