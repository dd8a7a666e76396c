#include "host/eval/metrics/evaluate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/eval/metrics/pose_error.hpp"

namespace binpick::eval {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Median of values (+inf counts: a hypothesis that matched nothing is as wrong as can be).
double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  const double upper = values[mid];
  if (values.size() % 2) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + mid);
  return (lower + upper) / 2;
}

double fraction(std::size_t part, std::size_t whole) {
  return whole ? double(part) / double(whole) : 0.0;
}

// Matches r to the instance of its obj_id whose nearest symmetric copy (pose_error.hpp) is
// nearest in translation, and measures its errors against that copy. Matching on the model
// origins alone fails for a part turned over about an axis away from its origin (a nut whose
// origin is on one face): its origin lands a part's height away, often nearer another part's.
void measure(HypothesisResult& r, const EvalImage& image, const bop::ModelInfo& model) {
  PoseError best{kInf, kInf};
  for (std::size_t i = 0; i < image.gt.size(); ++i) {
    const auto& g = image.gt[i];
    if (g.obj_id != r.obj_id) continue;
    const PoseError e = symmetric_pose_error(g.model_to_camera.R, g.model_to_camera.t, r.row.R,
                                             r.row.t, model.symmetries);
    if (e.translation_mm < best.translation_mm ||
        (e.translation_mm == best.translation_mm && e.rotation_deg < best.rotation_deg))
      best = e, r.gt_index = int(i);
  }
  if (r.gt_index < 0) {
    r.translation_mm = r.translation_pct = r.rotation_deg = kInf;
    return;
  }
  r.translation_mm = best.translation_mm;
  r.translation_pct = 100.0 * best.translation_mm / model.diameter;
  r.rotation_deg = best.rotation_deg;
}

PrecisionAt precision_at(const std::vector<HypothesisResult>& results, const OperatingPoint& at) {
  std::size_t all = 0, top = 0, tops = 0;
  for (const auto& r : results) {
    const bool ok = correct_at(r, at);
    all += ok;
    if (r.top) ++tops, top += ok;
  }
  return {at, fraction(all, results.size()), fraction(top, tops)};
}

}  // namespace

Landing landing(const EvalImage& image, const bop::ModelsInfo& models, int obj_id,
                const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  const auto own = models.find(obj_id);
  const Eigen::Vector3d own_centre =
      own == models.end() ? Eigen::Vector3d::Zero() : own->second.centre;
  const Eigen::Vector3d centre = R * own_centre + t;
  double nearest = kInf;
  Landing out = Landing::none;
  for (const auto& g : image.gt) {
    const auto model = models.find(g.obj_id);
    if (model == models.end()) continue;
    const auto& T = g.model_to_camera;
    const double d = (T.R * model->second.centre + T.t - centre).norm();
    if (d <= model->second.diameter / 2 && d < nearest)
      nearest = d, out = g.obj_id == obj_id ? Landing::part : Landing::distractor;
  }
  return out;
}

bool correct_at(const HypothesisResult& r, const OperatingPoint& at) {
  return r.translation_pct <= at.translation_pct + kThresholdSlack &&
         r.rotation_deg <= at.rotation_deg + kThresholdSlack;
}

void check(const EvalOptions& o) {
  for (const OperatingPoint* p : {&o.loose, &o.strict})
    if (!(p->translation_pct >= 0 && p->rotation_deg >= 0 && std::isfinite(p->translation_pct) &&
          std::isfinite(p->rotation_deg)))
      throw InputError("operating point thresholds must be finite and non-negative");
  if (!(o.vsd_delta_mm > 0 && std::isfinite(o.vsd_delta_mm)))
    throw InputError(fmt::format("the VSD delta {:g} mm must be positive and finite",
                                 o.vsd_delta_mm));
  if (!(o.score_keep > 0 && o.score_keep <= 1))
    throw InputError(fmt::format("the score calibration's kept fraction {:g} must be in (0, 1]",
                                 o.score_keep));
}

namespace {

// The figures of s.results, whose ranks, tops and times are set.
void summarize(EvalSummary& s, const EvalOptions& options) {
  std::vector<double> te_all, re_all, te_top, re_top;
  std::size_t tops = 0, all_distractor = 0, all_nothing = 0, top_distractor = 0, top_nothing = 0;
  for (const auto& r : s.results) {
    s.unmatched += r.gt_index < 0;
    all_distractor += r.landing == Landing::distractor;
    all_nothing += r.landing == Landing::none;
    if (r.top) {
      ++tops;
      top_distractor += r.landing == Landing::distractor;
      top_nothing += r.landing == Landing::none;
    }
    te_all.push_back(r.translation_pct), re_all.push_back(r.rotation_deg);
    if (r.top) te_top.push_back(r.translation_pct), re_top.push_back(r.rotation_deg);
  }
  s.all_on_distractor = fraction(all_distractor, s.results.size());
  s.all_on_nothing = fraction(all_nothing, s.results.size());
  s.top_on_distractor = fraction(top_distractor, tops);
  s.top_on_nothing = fraction(top_nothing, tops);
  s.loose = precision_at(s.results, options.loose);
  s.strict = precision_at(s.results, options.strict);
  s.score_loose = calibrate(s.results, options.loose, options.score_keep);
  s.score_strict = calibrate(s.results, options.strict, options.score_keep);
  s.median_translation_pct_all = median(te_all), s.median_rotation_deg_all = median(re_all);
  s.median_translation_pct_top = median(te_top), s.median_rotation_deg_top = median(re_top);
}

}  // namespace

EvalSummary evaluate(const Dataset& dataset, const std::vector<bop::ResultRow>& rows,
                     const EvalOptions& options) {
  check(options);
  EvalSummary s;
  s.images = dataset.images.size();
  s.results.reserve(rows.size());
  std::map<ImageKey, std::vector<std::size_t>> by_image;  // indices into s.results
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& row = rows[i];
    const ImageKey key{row.scene_id, row.im_id};
    const auto image = dataset.images.find(key);
    if (image == dataset.images.end())
      throw InputError(fmt::format(
          "results row {} is for scene {} image {}, which dataset {} does not have", i + 1,
          row.scene_id, row.im_id, dataset.root.string()));
    const auto model = dataset.models.find(row.obj_id);
    if (model == dataset.models.end())
      throw InputError(fmt::format("results row {} has obj_id {}, which {} lacks", i + 1,
                                   row.obj_id, (dataset.root / "models/models_info.json").string()));
    HypothesisResult r;
    r.scene_id = row.scene_id, r.im_id = row.im_id, r.obj_id = row.obj_id;
    r.score = row.score;
    r.row = row;
    measure(r, image->second, model->second);
    r.landing = landing(image->second, dataset.models, row.obj_id, row.R, row.t);
    auto& list = by_image[key];
    r.rank = int(list.size());
    list.push_back(s.results.size());
    s.results.push_back(r);
  }

  double total_ms = 0;
  for (const auto& [key, list] : by_image) {
    std::size_t best = list.front();
    for (std::size_t i : list)
      if (s.results[i].score > s.results[best].score) best = i;
    s.results[best].top = true;
    // The time column is per image (the same on each of its rows); rows may disagree if
    // concatenated from several runs: take the first.
    const double image_ms = 1e3 * s.results[list.front()].row.time;
    for (std::size_t i : list) s.results[i].ms = image_ms / double(list.size());
    total_ms += image_ms;
  }
  s.images_with_results = by_image.size();
  s.hypotheses = s.results.size();
  summarize(s, options);
  s.ms_per_hypothesis = s.hypotheses ? total_ms / double(s.hypotheses) : 0.0;
  return s;
}

std::vector<ObjectSummary> per_object(const Dataset& dataset, const EvalSummary& all,
                                      const EvalOptions& options) {
  std::map<int, EvalSummary> objects;
  for (const HypothesisResult& r : all.results) objects[r.obj_id].results.push_back(r);
  if (objects.size() < 2) return {};
  std::vector<ObjectSummary> out;
  for (auto& [obj_id, s] : objects) {
    // Ranks and the top-ranked row among this object's rows of each image.
    std::map<ImageKey, std::vector<std::size_t>> by_image;
    for (std::size_t i = 0; i < s.results.size(); ++i) {
      HypothesisResult& r = s.results[i];
      auto& list = by_image[{r.scene_id, r.im_id}];
      r.rank = int(list.size());
      r.top = false;
      list.push_back(i);
    }
    double ms = 0;
    for (const auto& [key, list] : by_image) {
      std::size_t best = list.front();
      for (std::size_t i : list) {
        if (s.results[i].score > s.results[best].score) best = i;
        ms += s.results[i].ms;
      }
      s.results[best].top = true;
    }
    for (const auto& [key, image] : dataset.images)
      s.images += std::any_of(image.gt.begin(), image.gt.end(),
                              [id = obj_id](const bop::GroundTruth& g) { return g.obj_id == id; });
    s.images_with_results = by_image.size();
    s.hypotheses = s.results.size();
    s.ms_per_hypothesis = ms / double(s.hypotheses);
    summarize(s, options);
    s.results.clear();  // `all` holds them
    out.push_back({obj_id, std::move(s)});
  }
  return out;
}

}  // namespace binpick::eval
