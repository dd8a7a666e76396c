#include "host/eval/report/scene_pictures.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "host/formats/mesh/load_model.hpp"
#include "host/train/surface_sampling.hpp"

namespace binpick::eval {
namespace {

std::vector<Eigen::Vector3d> posed(const std::vector<Eigen::Vector3f>& model,
                                   const HypothesisResult& h) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(model.size());
  for (const auto& p : model) out.push_back(h.row.R * p.cast<double>() + h.row.t);
  return out;
}

// Scales the labels with the picture so they stay readable on 1600 x 900 and on small tests.
int label_scale(const SceneView& v) { return std::max(1, int(v.depth_raw.width / 400)); }

void label(Canvas& c, const SceneView& v, const HypothesisResult& h, Rgb colour) {
  const auto uv = v.project(h.row.t);
  if (!uv) return;
  const int s = label_scale(v);
  c.text(int(uv->x()) + 4 * s, int(uv->y()) - 10 * s, std::to_string(h.rank + 1), s, colour);
}

}  // namespace

ModelSamples sample_models(const Dataset& dataset, std::size_t points_per_model) {
  ModelSamples out;
  for (const auto& [obj_id, info] : dataset.models) {
    const auto path = dataset.root / "models" / fmt::format("obj_{:06d}.ply", obj_id);
    if (!std::filesystem::exists(path)) continue;  // pictures then show no model points
    out[obj_id] = sample_surface(load_model(path.string(), {}), points_per_model).points;
  }
  return out;
}

Canvas depth_false_colour(const SceneView& v, DepthRange* range) {
  std::vector<double> valid;
  for (std::size_t i = 0; i < v.depth_raw.pixels.size(); ++i)
    if (v.depth_raw.pixels[i]) valid.push_back(v.depth_mm(i));
  Canvas c(v.depth_raw.width, v.depth_raw.height);
  if (valid.empty()) return c;
  // Percentiles, not min and max: a few stray pixels must not flatten the whole bin.
  auto at = [&](double q) {
    const auto k = std::size_t(q * double(valid.size() - 1));
    std::nth_element(valid.begin(), valid.begin() + std::ptrdiff_t(k), valid.end());
    return valid[k];
  };
  const double near = at(0.01), far = std::max(at(0.99), near + 1e-6);
  if (range) *range = {near, far};
  for (std::uint32_t y = 0; y < c.height(); ++y)
    for (std::uint32_t x = 0; x < c.width(); ++x) {
      const std::size_t i = std::size_t(y) * c.width() + x;
      if (v.depth_raw.pixels[i]) c.blend(int(x), int(y), viridis((v.depth_mm(i) - near) / (far - near)));
    }
  return c;
}

Canvas intensity_picture(const SceneView& v, double brightness) {
  if (v.gray.width) return Canvas::from_gray(v.gray, brightness);
  Canvas c = depth_false_colour(v);  // no intensity image: its luminance will do
  for (std::uint32_t y = 0; y < c.height(); ++y)
    for (std::uint32_t x = 0; x < c.width(); ++x) {
      const Rgb p = c.get(int(x), int(y));
      const auto g = std::uint8_t(std::min(255.0, (0.3 * p[0] + 0.59 * p[1] + 0.11 * p[2]) * brightness));
      c.blend(int(x), int(y), {g, g, g});
    }
  return c;
}

Canvas hypotheses_picture(const SceneView& v, const std::vector<const HypothesisResult*>& hyps,
                          double radius) {
  Canvas c = intensity_picture(v, 0.55);
  // Last rank first, so the first hypotheses stay on top where neighbourhoods overlap.
  for (auto it = hyps.rbegin(); it != hyps.rend(); ++it) {
    const HypothesisResult& h = **it;
    const Eigen::Vector3f t = h.row.t.cast<float>();
    const auto centre = v.project(h.row.t);
    if (!centre || h.row.t.z() <= radius) continue;
    // The sphere's image lies within this box around the projected centre.
    const double half = radius * std::max(v.K(0, 0), v.K(1, 1)) / (h.row.t.z() - radius) + 2;
    const int x0 = std::max(0, int(centre->x() - half)), x1 = std::min(int(c.width()) - 1, int(centre->x() + half));
    const int y0 = std::max(0, int(centre->y() - half)), y1 = std::min(int(c.height()) - 1, int(centre->y() + half));
    const Rgb colour = rank_colour(h.rank);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const auto& p = v.points[std::size_t(y) * c.width() + std::size_t(x)];
        if (p.z() > 0 && (p - t).norm() <= radius) c.blend(x, y, colour, 0.6);
      }
  }
  const int s = label_scale(v);
  for (const auto* h : hyps)
    if (const auto uv = v.project(h->row.t)) c.cross(uv->x(), uv->y(), 4 * s, std::max(1, s / 2), {255, 255, 255});
  for (const auto* h : hyps) label(c, v, *h, rank_colour(h->rank));
  return c;
}

Canvas detections_picture(const SceneView& v, const std::vector<const HypothesisResult*>& hyps,
                          const ModelSamples& models, double diameter, const OperatingPoint& at) {
  Canvas c = intensity_picture(v, 0.8);
  const double dot = 0.6 + 0.4 * label_scale(v);
  for (auto it = hyps.rbegin(); it != hyps.rend(); ++it) {
    const HypothesisResult& h = **it;
    const auto model = models.find(h.obj_id);
    if (model == models.end()) continue;
    const Rgb colour = correct_at(h, at) ? kCorrect : kWrong;
    for (const auto& p : posed(model->second, h))
      if (const auto uv = v.project(p)) c.disc(uv->x(), uv->y(), dot, colour, 0.7);
  }
  for (const auto* h : hyps) {
    const auto uv = v.project(h->row.t);
    if (!h->top || !uv) continue;
    const double r = 0.6 * diameter * v.K(0, 0) / std::max(1.0, h->row.t.z());
    c.ring(uv->x(), uv->y(), r, 1.5 * label_scale(v), kTopRing);
  }
  for (const auto* h : hyps) label(c, v, *h, h->top ? kTopRing : Rgb{255, 255, 255});
  return c;
}

}  // namespace binpick::eval
