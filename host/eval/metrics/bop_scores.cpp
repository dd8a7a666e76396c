#include "host/eval/metrics/bop_scores.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "host/eval/metrics/bop_pose_error.hpp"
#include "host/eval/metrics/bop_targets.hpp"
#include "host/eval/metrics/eval_vertices.hpp"
#include "host/formats/bop/bop_files.hpp"

namespace binpick::eval {
namespace {

namespace fs = std::filesystem;

// BOP's MSPD thresholds are for 640 px wide images; the toolkit takes the width from the
// dataset's camera (camera.json, or camera_SENSOR.json for a sensor).
void read_image_width(const Dataset& dataset, BopScores& scores) {
  const std::string sensor =
      dataset.images.empty() ? std::string() : dataset.images.begin()->second.files.sensor;
  const fs::path path =
      dataset.root / (sensor.empty() ? "camera.json" : "camera_" + sensor + ".json");
  if (!fs::exists(path)) return;
  const bop::Camera camera = bop::read_camera(path);
  if (camera.width == 0) return;
  scores.image_width = camera.width;
  scores.image_width_known = true;
}

// The rows of each (image, obj_id), in file order.
using RowGroups = std::map<std::pair<ImageKey, int>, std::vector<const bop::ResultRow*>>;

RowGroups group_rows(const std::vector<bop::ResultRow>& rows) {
  RowGroups groups;
  for (const auto& r : rows) groups[{{r.scene_id, r.im_id}, r.obj_id}].push_back(&r);
  return groups;
}

// What one (image, obj_id) group needs from the whole evaluation.
struct Measure {
  const EvalImage& image;
  const std::vector<bool>& is_target;
  const std::vector<Eigen::Vector3d>& vertices;
  const std::vector<SymmetryTransform>& symmetries;
  double diameter, mspd_scale;
};

// The rows BOP considers: the inst_count best-scored (stable: file order on ties).
std::vector<const bop::ResultRow*> considered_rows(const RowGroups& rows, const ImageKey& key,
                                                   int obj_id, int inst_count) {
  std::vector<const bop::ResultRow*> chosen;
  if (const auto it = rows.find({key, obj_id}); it != rows.end()) chosen = it->second;
  std::stable_sort(chosen.begin(), chosen.end(),
                   [](const auto* a, const auto* b) { return a->score > b->score; });
  if (chosen.size() > static_cast<std::size_t>(inst_count)) chosen.resize(inst_count);
  return chosen;
}

// Appends the errors of `row` to every target instance of obj_id to both groups, normalised as
// BOP thresholds them. Errors at or above the largest threshold match nothing, so they are not
// measured exactly (the margin keeps an error just below a threshold, in either arithmetic,
// measured).
void measure_row(const bop::ResultRow& row, int obj_id, const Measure& m, TargetGroup& mssd_group,
                 TargetGroup& mspd_group) {
  constexpr double kMargin = 1 + 1e-9;
  const double mssd_bound = bop_mssd_thresholds().back() * m.diameter * kMargin;
  const double mspd_bound = bop_mspd_thresholds().back() / m.mspd_scale * kMargin;
  EstimateErrors e_mssd, e_mspd;
  const RigidPose est{row.R, row.t};
  for (std::size_t i = 0; i < m.image.gt.size(); ++i) {
    if (!m.is_target[i] || m.image.gt[i].obj_id != obj_id) continue;
    const RigidPose gt{m.image.gt[i].model_to_camera.R, m.image.gt[i].model_to_camera.t};
    const int index = static_cast<int>(i);
    e_mssd.errors.emplace_back(
        index, mssd(est, gt, m.vertices, m.symmetries, mssd_bound) / m.diameter);
    e_mspd.errors.emplace_back(
        index, m.mspd_scale * mspd(est, gt, m.image.camera.K, m.vertices, m.symmetries, mspd_bound));
  }
  mssd_group.estimates.push_back(std::move(e_mssd));
  mspd_group.estimates.push_back(std::move(e_mspd));
}

}  // namespace

std::vector<double> bop_mssd_thresholds() { return arange(0.05, 0.51, 0.05); }
std::vector<double> bop_mspd_thresholds() { return arange(5, 51, 5); }

BopScores bop_scores(const Dataset& dataset, const std::vector<bop::ResultRow>& rows,
                     const BopOptions& options) {
  BopScores scores;
  const TargetSet targets = bop_targets(dataset);
  scores.targets_source = targets.source;
  read_image_width(dataset, scores);
  std::set<int> obj_ids;
  for (const auto& [key, objects] : targets.targets)
    for (const auto& [obj_id, count] : objects) obj_ids.insert(obj_id);
  scores.vertices = eval_vertices_directory(dataset.root, obj_ids);
  if (const auto missing = first_missing_model(scores.vertices, obj_ids); !missing.empty()) {
    scores.unavailable = "no " + missing.string();
    return scores;
  }
  const EvalVertices vertices = load_eval_vertices(dataset.root, obj_ids);
  std::map<int, std::vector<SymmetryTransform>> symmetries;
  for (int id : obj_ids) symmetries[id] = bop_symmetry_transforms(dataset.models.at(id).symmetries);

  const RowGroups rows_by_group = group_rows(rows);
  std::vector<TargetGroup> mssd_groups, mspd_groups;
  std::vector<ScoredGroup> scored;  // what VSD renders and compares
  for (const auto& [key, objects] : targets.targets) {
    const EvalImage& image = dataset.images.at(key);
    const std::vector<bool> is_target = target_instances(image, objects);
    for (const auto& [obj_id, inst_count] : objects) {
      TargetGroup mssd_group{obj_id, 0, {}};
      for (std::size_t i = 0; i < image.gt.size(); ++i)
        mssd_group.targets += is_target[i] && image.gt[i].obj_id == obj_id;
      TargetGroup mspd_group = mssd_group;
      scores.targets += mssd_group.targets;
      const Measure m{image, is_target, vertices.by_object.at(obj_id), symmetries.at(obj_id),
                      dataset.models.at(obj_id).diameter, 640.0 / scores.image_width};
      const auto chosen = considered_rows(rows_by_group, key, obj_id, inst_count);
      scores.estimates += static_cast<int>(chosen.size());
      for (const auto* row : chosen) measure_row(*row, obj_id, m, mssd_group, mspd_group);
      scored.push_back({key, obj_id, chosen, {}});
      for (std::size_t i = 0; i < image.gt.size(); ++i)
        if (is_target[i] && image.gt[i].obj_id == obj_id) scored.back().targets.push_back(int(i));
      mssd_groups.push_back(std::move(mssd_group));
      mspd_groups.push_back(std::move(mspd_group));
    }
  }
  scores.mssd = recall_over_thresholds(mssd_groups, bop_mssd_thresholds());
  scores.mspd = recall_over_thresholds(mspd_groups, bop_mspd_thresholds());
  scores.average_recall = (scores.mssd.overall.average + scores.mspd.overall.average) / 2.0;
  if (!options.vsd) return scores;
  scores.vsd = bop_vsd_recall(dataset, scored, scores.vertices, options.vsd_delta_mm);
  scores.has_vsd = scores.vsd.unavailable.empty();
  if (scores.has_vsd)
    scores.average_recall =
        (scores.vsd.average + scores.mssd.overall.average + scores.mspd.overall.average) / 3.0;
  return scores;
}

}  // namespace binpick::eval
