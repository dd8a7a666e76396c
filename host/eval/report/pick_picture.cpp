#include "host/eval/report/pick_picture.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "host/core/gripper.hpp"
#include "host/formats/grasps/grasp_json.hpp"

namespace binpick::eval {
namespace {

constexpr int kRimPoints = 32;  // a cylinder's rim as a polygon

using Outline = std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>;  // segments, grasp frame

Eigen::Vector3d rim(const GripperSolid& s, double z, int k) {
  const double a = 2 * std::numbers::pi * k / kRimPoints;
  return s.centre + Eigen::Vector3d(s.half.x() * std::cos(a), s.half.y() * std::sin(a), z);
}

// A box's twelve edges; a cylinder's two rims and four lines along it.
Outline outline(const GripperSolid& s) {
  Outline out;
  if (s.shape == GripperSolid::Shape::cylinder) {
    for (int k = 0; k < kRimPoints; ++k)
      for (double z : {-s.half.z(), s.half.z()}) out.emplace_back(rim(s, z, k), rim(s, z, k + 1));
    for (int k = 0; k < kRimPoints; k += kRimPoints / 4)
      out.emplace_back(rim(s, -s.half.z(), k), rim(s, s.half.z(), k));
    return out;
  }
  for (int axis = 0; axis < 3; ++axis)
    for (int u : {-1, 1})
      for (int w : {-1, 1}) {
        Eigen::Vector3d a, b;
        a[axis] = -1, b[axis] = 1;
        a[(axis + 1) % 3] = b[(axis + 1) % 3] = u;
        a[(axis + 2) % 3] = b[(axis + 2) % 3] = w;
        out.emplace_back(s.centre + s.half.cwiseProduct(a), s.centre + s.half.cwiseProduct(b));
      }
  return out;
}

// The crop of the image the picture shows, magnified: pixel = (image pixel - origin) * zoom.
struct Window {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double zoom = 1;
  std::optional<Eigen::Vector2d> at(const SceneView& v, const Eigen::Vector3d& p) const {
    const auto uv = v.project(p);
    if (!uv) return std::nullopt;
    return Eigen::Vector2d((*uv - origin) * zoom);
  }
};

// Around every pick's grasp point, a diameter and a half each way (the gripper and its
// neighbours), magnified to about kPickPanel pixels across.
constexpr double kPickPanel = 640;
Window window(const SceneView& v, const std::vector<const PickOutcome*>& picks, double diameter,
              int& width, int& height) {
  Eigen::Vector2d lo(v.depth_raw.width, v.depth_raw.height), hi(0, 0);
  for (const PickOutcome* o : picks) {
    const Eigen::Vector3d t = o->pick.grasp.translation();
    const auto uv = v.project(t);
    if (!uv) continue;
    const double r = 1.5 * diameter * v.K(0, 0) / std::max(1.0, t.z());
    lo = lo.cwiseMin(*uv - Eigen::Vector2d(r, r));
    hi = hi.cwiseMax(*uv + Eigen::Vector2d(r, r));
  }
  const Eigen::Vector2d size(v.depth_raw.width, v.depth_raw.height);
  lo = lo.cwiseMax(Eigen::Vector2d::Zero()).array().floor();
  hi = hi.cwiseMin(size).array().ceil();
  if (!(hi.array() > lo.array()).all()) lo.setZero(), hi = size;  // nothing in view: all of it
  Window w{lo, std::clamp(std::floor(kPickPanel / (hi - lo).maxCoeff()), 1.0, 8.0)};
  width = int((hi.x() - lo.x()) * w.zoom);
  height = int((hi.y() - lo.y()) * w.zoom);
  return w;
}

void draw_pick(Canvas& c, const SceneView& v, const Window& win, const PickOutcome& o,
               double diameter, double scale) {
  const Rgb colour = o.success() ? kCorrect : kWrong;
  const Gripper gripper = parse_gripper(o.pick.gripper);
  Grasp g;  // the grasp's own frame: the solids are drawn through o.pick.grasp
  g.kind = gripper.kind;
  g.size = gripper.a;
  const auto px = [&](const Eigen::Vector3d& local) { return win.at(v, o.pick.grasp * local); };
  // The footprint: a suction cup's disc, or each finger's tip, on the grasp plane.
  std::vector<Eigen::Vector2d> disc;
  for (int k = 0; k < kRimPoints && gripper.kind == Grasp::Kind::suction; ++k)
    if (const auto p = px(Eigen::Vector3d(gripper.a / 2 * std::cos(2 * std::numbers::pi * k / kRimPoints),
                                          gripper.a / 2 * std::sin(2 * std::numbers::pi * k / kRimPoints), 0)))
      disc.push_back(*p);
  c.polygon(disc, colour, 0.55);
  for (const GripperSolid& s : gripper.solids(g))
    for (const auto& [a, b] : outline(s)) {
      const auto pa = px(a), pb = px(b);
      if (pa && pb) c.line(pa->x(), pa->y(), pb->x(), pb->y(), scale, colour, 0.8);
    }
  // The approach: from half a diameter above the tool's top down to the grasp point.
  const auto tail = px(Eigen::Vector3d(0, 0, -gripper.length() - diameter / 2));
  const auto head = px(Eigen::Vector3d::Zero());
  if (!tail || !head) return;
  c.line(tail->x(), tail->y(), head->x(), head->y(), 1.5 * scale, {255, 255, 255});
  const Eigen::Vector2d back = *tail - *head;
  if (back.norm() > 1) {
    const Eigen::Vector2d u = back.normalized() * 8 * scale;
    for (double turn : {-0.45, 0.45}) {
      const Eigen::Vector2d w = Eigen::Rotation2Dd(turn) * u;
      c.line(head->x(), head->y(), head->x() + w.x(), head->y() + w.y(), 1.5 * scale, {255, 255, 255});
    }
  }
  c.disc(head->x(), head->y(), 2 * scale, colour);
}

}  // namespace

Canvas picks_picture(const SceneView& v, const std::vector<const PickOutcome*>& picks,
                     const std::vector<const HypothesisResult*>& hyps, const ModelSamples& models,
                     double diameter) {
  int width = 0, height = 0;
  const Window win = window(v, picks, diameter, width, height);
  const Canvas image = intensity_picture(v, 0.7);
  Canvas c{std::uint32_t(width), std::uint32_t(height)};
  for (int y = 0; y < height; ++y)  // the crop, magnified pixel for pixel
    for (int x = 0; x < width; ++x)
      c.blend(x, y, image.get(int(win.origin.x() + x / win.zoom), int(win.origin.y() + y / win.zoom)));
  const double scale = std::max(1.0, width / 400.0);
  for (const PickOutcome* o : picks)
    for (const HypothesisResult* h : hyps) {
      const auto model = models.find(h->obj_id);
      if (h->obj_id != o->pick.obj_id || h->rank != o->pick.rank || model == models.end()) continue;
      for (const auto& p : model->second)
        if (const auto uv = win.at(v, h->row.R * p.cast<double>() + h->row.t))
          c.disc(uv->x(), uv->y(), 0.6 * scale, kModelPoints, 0.4);
    }
  for (const PickOutcome* o : picks) draw_pick(c, v, win, *o, diameter, scale);
  for (const PickOutcome* o : picks)
    if (const auto uv = win.at(v, o->pick.grasp.translation()))
      c.text(int(uv->x() + 6 * scale), int(uv->y() - 14 * scale), std::to_string(o->pick.rank + 1),
             std::max(2, int(scale)), o->success() ? kCorrect : kWrong);
  return c;
}

}  // namespace binpick::eval
