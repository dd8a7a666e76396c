#include <algorithm>
#include <cmath>
#include <string>

#include "host/core/error.hpp"
#include "host/core/timing.hpp"
#include "host/core/diameter.hpp"
#include "host/core/cloud_input.hpp"
#include "host/train/suction_grasps.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/lookalikes.hpp"
#include "host/train/surface_sampling.hpp"
#include "host/train/symmetry_detect.hpp"
#include "host/train/edge_probes.hpp"
#include "host/train/lookalike_probes.hpp"
#include "host/train/probe_surface.hpp"
#include "host/train/voxel_subsample.hpp"

namespace binpick {
void check_train_params(const PpfTrainParams& p) {
  if (!(p.voxel_ratio > 0 && p.voxel_ratio <= 1))
    throw InputError("voxel ratio " + std::to_string(p.voxel_ratio) +
                     " must be in (0, 1] (a fraction of the diameter; the paper uses 0.05)");
  make_ppf_quant(1.0f, p.distance_steps, p.angle_steps);
  if (!(std::isfinite(p.cup_diameter) && p.cup_diameter >= 0 && p.cup_diameter < 1e6))
    throw InputError("cup diameter " + std::to_string(p.cup_diameter) +
                     " must be positive (mm), or 0 for " +
                     std::to_string(int(100 * kDefaultCupRatio)) + " % of the diameter");
}

PpfModel train_ppf_model(const Mesh& mesh, const PpfTrainParams& params, PpfTrainStats* stats,
                         ocl::Device& dev) {
  check_train_params(params);
  PpfTrainStats st;
  Stopwatch clock;
  PpfModel model;
  model.diameter = static_cast<float>(exact_diameter(mesh.positions));
  if (!(model.diameter > 0 && std::isfinite(model.diameter)))
    throw InputError("the model has no extent (diameter " + std::to_string(model.diameter) + ")");
  model.voxel_size = static_cast<float>(params.voxel_ratio * model.diameter);
  model.quant = make_ppf_quant(model.diameter, params.distance_steps, params.angle_steps);
  st.diameter_s = clock.lap_seconds();

  const double voxel_areas = surface_area(mesh) / (double(model.voxel_size) * model.voxel_size);
  if (voxel_areas > 8.0 * kMaxPpfModelPoints)
    throw InputError("voxel ratio " + std::to_string(params.voxel_ratio) +
                     " is too fine: the model would have about " +
                     std::to_string(std::llround(voxel_areas)) + " points, at most " +
                     std::to_string(kMaxPpfModelPoints) + " are supported");
  const PointCloud dense = sample_surface(mesh, model_surface_samples(surface_area(mesh), model.voxel_size));
  st.surface_samples = dense.points.size();
  st.sample_s = clock.lap_seconds();

  // Stored exactly as the table saw them (unit normals), for detection to use.
  // Both faces: a wall thinner than a voxel (sheet metal, a tube) must be seen from either side.
  model.cloud =
      with_unit_normals(voxel_subsample(dev, dense, model.voxel_size, VoxelFaces::both).cloud);
  st.subsample_s = clock.lap_seconds();
  if (model.cloud.points.size() > kMaxPpfModelPoints)
    throw InputError("voxel ratio " + std::to_string(params.voxel_ratio) + " gives " +
                     std::to_string(model.cloud.points.size()) + " model points, at most " +
                     std::to_string(kMaxPpfModelPoints) + " are supported: raise it");

  model.fit_cloud = with_unit_normals(
      voxel_subsample(dev, dense, model.voxel_size / kFitVoxelDivisor, VoxelFaces::both).cloud);
  model.table = build_ppf_table(dev, model.cloud, model.quant, &st.table);
  clock.lap_seconds();
  model.symmetries = find_symmetries(mesh);
  st.symmetry_s = clock.lap_seconds();
  model.lookalikes = find_lookalikes(model.cloud, model.voxel_size, model.symmetries);
  st.lookalike_s = clock.lap_seconds();
  // One dense probe surface for both kinds of probe.
  const ProbeSurface probe_dense = probe_surface(mesh, model.voxel_size, dev);
  const LookalikeProbes probes = find_lookalike_probes(probe_dense, model.lookalikes);
  model.lookalike_probes = probes.cloud;
  model.probe_lookalike = probes.twin;
  const EdgeProbes edges = find_edge_probes(probe_dense, dev);
  model.edge_probes = edges.cloud;
  model.edge_probe_rim = edges.rim;
  st.probe_s = clock.lap_seconds();
  model.grasps = find_suction_grasps(
      model.fit_cloud, suction_grasp_options(model.diameter, model.voxel_size, params.cup_diameter));
  st.grasp_s = clock.lap_seconds();
  st.points = model.cloud.points.size();
  st.pairs = st.points * (st.points > 0 ? st.points - 1 : 0);
  st.entries = model.table.entries.size();
  st.distinct_keys = model.table.distinct_keys();
  if (stats) *stats = st;
  return model;
}

}  // namespace binpick
