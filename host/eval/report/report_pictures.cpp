#include "host/eval/report/report_pictures.hpp"

#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/eval/report/pick_picture.hpp"

namespace binpick::eval {
namespace {

// The images to picture: the first ones (in id order) that have results, then, if too few have,
// the first ones without.
std::vector<ImageKey> images_to_picture(const DatasetEvaluation& e, int count) {
  std::map<ImageKey, bool> has_results;
  for (const auto& r : e.summary.results) has_results[{r.scene_id, r.im_id}] = true;
  std::vector<ImageKey> keys;
  for (const auto& [key, _] : has_results)
    if (int(keys.size()) < count) keys.push_back(key);
  for (const auto& [key, _] : e.dataset.images)
    if (int(keys.size()) < count && !has_results.count(key)) keys.push_back(key);
  return keys;
}

}  // namespace

std::vector<PicturedImage> write_pictures(const DatasetEvaluation& e, std::size_t d,
                                          const ReportOptions& options,
                                          std::vector<std::string>& warnings) {
  std::vector<PicturedImage> out;
  if (options.pictures <= 0) return out;
  const auto keys = images_to_picture(e, options.pictures);
  if (keys.empty()) return out;
  std::filesystem::create_directories(options.out / "pictures");
  ModelSamples models;  // without them the pictures still show the scene and hypotheses
  try {
    models = sample_models(e.dataset);
  } catch (const InputError& err) {
    warnings.push_back(fmt::format("no model points in the pictures of {}: {}", e.dataset.label, err.what()));
  }
  for (const ImageKey& key : keys) {
    std::vector<const HypothesisResult*> hyps;  // in rank order (file order within an image)
    for (const auto& r : e.summary.results)
      if (r.scene_id == key.scene_id && r.im_id == key.im_id) hyps.push_back(&r);
    const int obj_id = hyps.empty() ? e.dataset.models.begin()->first : hyps.front()->obj_id;
    const double diameter = e.dataset.models.at(obj_id).diameter;

    SceneView view;
    try {
      view = load_scene_view(e.dataset, key);
    } catch (const InputError& err) {
      warnings.push_back(fmt::format("no pictures of {} scene {} image {}: {}",
                                     e.dataset.label, key.scene_id, key.im_id, err.what()));
      continue;
    }
    PicturedImage p;
    p.dataset = d;
    p.key = key;
    const std::string stem = fmt::format("pictures/d{}_{:06d}_{:06d}_", d, key.scene_id, key.im_id);
    auto write = [&](const std::string& kind, const Canvas& canvas) {
      write_png(options.out / (stem + kind + ".png"), canvas.image());
      return stem + kind + ".png";
    };
    p.depth = write("depth", depth_false_colour(view, &p.depth_range));
    p.intensity = write("intensity", intensity_picture(view));
    p.hypotheses = write("hypotheses", hypotheses_picture(view, hyps, diameter));
    p.detections = write("detections", detections_picture(view, hyps, models, diameter, options.eval.loose));
    if (!hyps.empty()) p.closeup = write("closeup", closeup_picture(view, hyps, models, diameter));
    if (e.picks)
      for (const PickOutcome& o : e.picks->firsts)
        if (o.pick.scene_id == key.scene_id && o.pick.im_id == key.im_id) p.judged.push_back(&o);
    if (!p.judged.empty()) p.picks = write("picks", picks_picture(view, p.judged, hyps, models, diameter));
    out.push_back(p);
  }
  return out;
}

}  // namespace binpick::eval
