#include "host/eval/metrics/bop_vsd_recall.hpp"

#include <chrono>
#include <map>
#include <set>

#include "host/core/error.hpp"
#include "host/core/mesh_normals.hpp"
#include "host/core/read_file.hpp"
#include "host/eval/metrics/eval_vertices.hpp"
#include "host/eval/metrics/vsd_rendering.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/formats/mesh/mesh_readers.hpp"

namespace binpick::eval {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The groups of each image, in the order given.
std::map<ImageKey, std::vector<const ScoredGroup*>> by_image(const std::vector<ScoredGroup>& groups) {
  std::map<ImageKey, std::vector<const ScoredGroup*>> out;
  for (const auto& g : groups) out[g.image].push_back(&g);
  return out;
}

RigidPose gt_pose(const EvalImage& image, int index) {
  const auto& T = image.gt[std::size_t(index)].model_to_camera;
  return {T.R, T.t};
}

// What one image needs rendered: each estimate and each target that has at least one pair whose
// sphere images overlap, once, and for each pair whether it does.
struct ImagePlan {
  std::vector<PosedObject> objects;
  std::map<const bop::ResultRow*, std::size_t> estimate_slot;
  std::map<int, std::size_t> target_slot;
  std::set<std::pair<const bop::ResultRow*, int>> overlapping;
};

ImagePlan plan_image(const EvalImage& image, const std::vector<const ScoredGroup*>& groups,
                     const Dataset& dataset) {
  ImagePlan plan;
  for (const ScoredGroup* g : groups) {
    const double radius = 0.5 * dataset.models.at(g->obj_id).diameter;
    for (const auto* row : g->rows)
      for (int target : g->targets) {
        if (!sphere_projections_overlap(radius, row->t, gt_pose(image, target).t)) continue;
        plan.overlapping.insert({row, target});
        if (plan.estimate_slot.emplace(row, plan.objects.size()).second)
          plan.objects.push_back({g->obj_id, {row->R, row->t}});
        if (plan.target_slot.emplace(target, plan.objects.size()).second)
          plan.objects.push_back({g->obj_id, gt_pose(image, target)});
      }
  }
  return plan;
}

// The meshes as the files hold them (no repair: the toolkit renders them as they are), with
// normals only because the renderer takes them. Empty with `why` set if a file has no triangles
// (a point cloud has vertices for MSSD and MSPD but no surface to render).
std::map<int, Mesh> read_meshes(const std::vector<ScoredGroup>& groups, const fs::path& dir,
                                std::string& why) {
  std::map<int, Mesh> meshes;
  for (const auto& g : groups) {
    if (meshes.count(g.obj_id)) continue;
    const fs::path path = bop_model_path(dir, g.obj_id);
    Mesh mesh;
    try {
      mesh = read_ply(read_file_bytes(path));
    } catch (const InputError& e) {
      throw InputError(path.string() + ": " + e.what());
    }
    if (mesh.triangles.empty()) {
      why = path.string() + " has no triangles to render";
      return {};
    }
    if (mesh.normals.size() != mesh.positions.size()) compute_crease_normals(mesh);
    meshes[g.obj_id] = std::move(mesh);
  }
  return meshes;
}

VsdRecall vsd_recall(const Dataset& dataset, const std::vector<ScoredGroup>& groups,
                     const fs::path& models_dir, double delta_mm) {
  VsdRecall out;
  const auto images = by_image(groups);
  for (const auto& [key, image_groups] : images)
    if (const auto path = dataset.images.at(key).files.depth(key.im_id); !fs::exists(path)) {
      out.unavailable = "no " + path.string();
      return out;
    }
  auto meshes = read_meshes(groups, models_dir, out.unavailable);
  if (!out.unavailable.empty()) return out;
  VsdSettings settings;
  settings.delta_mm = out.delta_mm = delta_mm;
  out.taus = settings.taus;
  ModelDepthRenderer renderer(std::move(meshes));

  std::vector<std::vector<TargetGroup>> tau_groups(settings.taus.size());
  for (const auto& [key, image_groups] : images) {
    const EvalImage& image = dataset.images.at(key);
    const ImagePlan plan = plan_image(image, image_groups, dataset);
    const auto depth = read_png16(image.files.depth(key.im_id));
    const BopDepthImage test{depth.width, depth.height, &depth.pixels, image.camera.depth_scale};
    auto start = Clock::now();
    const auto silhouettes = renderer.render(image.camera.K, depth.width, depth.height, plan.objects);
    out.render_ms += ms_since(start);
    out.renders += int(plan.objects.size());

    start = Clock::now();
    for (const ScoredGroup* g : image_groups) {
      std::vector<TargetGroup> per_tau(settings.taus.size(),
                                       TargetGroup{g->obj_id, int(g->targets.size()), {}});
      settings.diameter = dataset.models.at(g->obj_id).diameter;
      for (const auto* row : g->rows) {
        for (auto& t : per_tau) t.estimates.emplace_back();
        for (int target : g->targets) {
          std::vector<double> errors(settings.taus.size(), 1.0);
          if (plan.overlapping.count({row, target})) {
            errors = vsd_errors(silhouettes[plan.estimate_slot.at(row)],
                                silhouettes[plan.target_slot.at(target)], test, image.camera.K,
                                settings);
            ++out.pairs_compared;
          } else {
            ++out.pairs_skipped;
          }
          for (std::size_t k = 0; k < errors.size(); ++k)
            per_tau[k].estimates.back().errors.emplace_back(target, errors[k]);
        }
      }
      for (std::size_t k = 0; k < per_tau.size(); ++k) tau_groups[k].push_back(std::move(per_tau[k]));
    }
    out.compare_ms += ms_since(start);
  }
  for (const auto& groups_at_tau : tau_groups)
    out.by_tau.push_back(recall_over_thresholds(groups_at_tau, bop_vsd_thresholds()));
  double sum = 0;
  for (const auto& m : out.by_tau) sum += m.overall.average;
  out.average = out.by_tau.empty() ? 0 : sum / double(out.by_tau.size());
  return out;
}

}  // namespace

double object_vsd_average(const VsdRecall& vsd, std::size_t i) {
  if (vsd.by_tau.empty()) return 0;
  double sum = 0;
  for (const auto& m : vsd.by_tau) sum += m.objects.at(i).curve.average;
  return sum / double(vsd.by_tau.size());
}

VsdRecall bop_vsd_recall(const Dataset& dataset, const std::vector<ScoredGroup>& groups,
                         const fs::path& models_dir, double delta_mm) {
  try {
    return vsd_recall(dataset, groups, models_dir, delta_mm);
  } catch (const DeviceError& e) {
    // eval's other figures need no device: without Vulkan they are still given.
    VsdRecall out;
    out.unavailable = std::string("no Vulkan rendering (") + e.what() + ")";
    return out;
  }
}

}  // namespace binpick::eval
