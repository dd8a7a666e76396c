// The trained PPF model of a part: its subsampled surface points with normals, the feature
// discretisation and the hash table, everything detection needs (Drost 2010; paper IV).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/grasp.hpp"
#include "host/core/mesh.hpp"
#include "host/core/symmetry.hpp"
#include "host/train/ppf_table.hpp"
#include "kernels/binpick_shared.h"

namespace binpick {

struct PpfModel {
  float diameter = 0;    // exact diameter of the mesh; quant.max_distance
  float voxel_size = 0;  // subsampling resolution (mm)
  bp_ppf_quant quant{};
  PointCloud cloud;      // model points m_i with unit normals; entries' `point` indexes them
  PpfTable table;        // key -> entries (m_r, alpha_m), CSR
  // The part's rotational symmetries in the model frame (find_symmetries), so that detection
  // clusters symmetric poses as one. Empty for a part without any, or a version 1 file.
  PartSymmetries symmetries;
  // The points refinement and verification compare with the depth image: the surface at half
  // the voxel (both faces), four times as many as `cloud`, so that a pose's fit averages over
  // more pixels (at 5 % noise, half the rotation error). Empty in files before version 3:
  // detection then uses `cloud`.
  PointCloud fit_cloud;
  // Look-alike poses (lookalikes.hpp): model-frame transforms x -> S x under which most of
  // the surface, but not all of it, maps onto itself; detection verifies each candidate's
  // look-alikes too. Found on `cloud`, also when reading a file before version 4.
  std::vector<Eigen::Isometry3d> lookalikes;
  // The points that tell a pose from each look-alike (lookalike_probes.hpp); probe_lookalike[i] indexes
  // lookalikes. Empty in files before version 4: detection then has no look-alike holes.
  PointCloud lookalike_probes;
  std::vector<std::uint32_t> probe_lookalike;
  // Points just beyond the part's edges (edge_probes.hpp), for the edge step of thin parts (its
  // face probes) and the in-plane search (all). edge_probe_rim[i] is 1 for a rim probe, 0 for a
  // face probe. Empty in files before version 5: detection then has no edge step; the kinds are
  // empty in version 5 files, where every probe counts as a face probe.
  PointCloud edge_probes;
  std::vector<std::uint8_t> edge_probe_rim;
  // Where a gripper may take the part (grasp.hpp): from a grasps file given to train, else the
  // suction grasps its flat faces offer (suction_grasps.hpp). Empty in files before version 7.
  std::vector<Grasp> grasps;

  // How many edge probes are face probes (all, without kinds).
  std::size_t edge_face_probes() const {
    std::size_t n = edge_probes.points.size();
    for (const std::uint8_t r : edge_probe_rim) n -= r != 0;
    return n;
  }
};

struct PpfTrainParams {
  double voxel_ratio = 0.05;  // voxel size / diameter
  std::uint32_t distance_steps = BP_PPF_DEFAULT_DIST_STEPS;
  std::uint32_t angle_steps = BP_PPF_DEFAULT_ANGLE_STEPS;
  // The suction cup the generated grasps are for (mm); 0: kDefaultCupRatio of the diameter, a
  // cup that fits a bolt's shank or a tube lying on its side as well as the flat faces.
  double cup_diameter = 0;
};

inline constexpr double kDefaultCupRatio = 0.1;
// How far from flat the surface under a cup may be (the lip's give), a fraction of the cup.
inline constexpr double kGraspFlatnessRatio = 0.15;
// Generated grasps on one face lie at least this fraction of the diameter apart (or a cup).
inline constexpr double kGraspApartRatio = 0.15;

struct PpfTrainStats {
  std::size_t surface_samples = 0;
  std::size_t points = 0;       // after voxel subsampling
  std::size_t pairs = 0;        // ordered pairs considered, points * (points - 1)
  std::size_t entries = 0;      // pairs in the table
  std::size_t distinct_keys = 0;
  double diameter_s = 0, sample_s = 0, subsample_s = 0, grasp_s = 0;
  double symmetry_s = 0, lookalike_s = 0, probe_s = 0;  // the look-alikes' and edges' probes
  PpfTableTimes table;
};

// Surface samples per voxel face area before subsampling: enough that nearly every voxel the
// surface crosses gets a sample close to its centre.
inline constexpr double kSamplesPerVoxelArea = 16.0;
// The refinement points' voxel is the model's divided by this (PpfModel::fit_cloud).
inline constexpr float kFitVoxelDivisor = 2.0f;

// The dense surface sample training subsamples (kSamplesPerVoxelArea per voxel face area).
inline std::size_t model_surface_samples(double surface_area, double voxel_size) {
  return std::max<std::size_t>(
      1, static_cast<std::size_t>(std::ceil(kSamplesPerVoxelArea * surface_area / (voxel_size * voxel_size))));
}

// Throws InputError unless voxel_ratio is finite in (0, 1] and the steps are in range
// (make_ppf_quant).
void check_train_params(const PpfTrainParams& params);

// Samples the surface, voxel-subsamples it, builds the table on dev (the process's shared
// device unless a caller, such as a test, picks another) and finds the part's symmetries
// (find_symmetries, last: bad parameters fail before it). Throws
// InputError for bad parameters, a degenerate mesh, or a voxel so small that the model would
// exceed kMaxPpfModelPoints points.
PpfModel train_ppf_model(const Mesh& mesh, const PpfTrainParams& params,
                         PpfTrainStats* stats = nullptr, ocl::Device& dev = ocl::Device::shared());

}  // namespace binpick
