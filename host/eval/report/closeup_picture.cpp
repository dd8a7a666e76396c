// closeup_picture (declared in scene_pictures.hpp): the paper's Figure 3, a detected model (pink)
// in the scene point cloud (blue), from two viewpoints, as point splats with a z-buffer.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>

#include "host/eval/report/scene_pictures.hpp"

namespace binpick::eval {
namespace {

constexpr int kPanel = 520;  // pixels a side of each view

struct Splat {
  Eigen::Vector3d p;  // relative to the detection's centre, camera frame
  Rgb colour;
  double bias;  // mm towards the viewer: model points win where they lie on the scene surface
};

// One orthographic view of the splats, rotated by R about the centre, into canvas at x offset.
void draw_view(Canvas& canvas, int x_offset, const std::vector<Splat>& splats,
               const Eigen::Matrix3d& R, double scale, double radius_px) {
  std::vector<double> zbuf(std::size_t(kPanel) * kPanel, std::numeric_limits<double>::infinity());
  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
  std::vector<Eigen::Vector3d> q(splats.size());
  for (std::size_t i = 0; i < splats.size(); ++i) {
    q[i] = R * splats[i].p;
    zmin = std::min(zmin, q[i].z()), zmax = std::max(zmax, q[i].z());
  }
  const int r = int(std::ceil(radius_px));
  for (std::size_t i = 0; i < splats.size(); ++i) {
    const double cx = kPanel / 2.0 + scale * q[i].x(), cy = kPanel / 2.0 + scale * q[i].y();
    const double z = q[i].z() - splats[i].bias;
    // Nearer is brighter, so the shape reads without normals.
    const double shade = 1.0 - 0.55 * (q[i].z() - zmin) / std::max(1e-9, zmax - zmin);
    const Rgb c{std::uint8_t(splats[i].colour[0] * shade), std::uint8_t(splats[i].colour[1] * shade),
                std::uint8_t(splats[i].colour[2] * shade)};
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        if (dx * dx + dy * dy > radius_px * radius_px) continue;
        const int x = int(std::lround(cx)) + dx, y = int(std::lround(cy)) + dy;
        if (x < 0 || y < 0 || x >= kPanel || y >= kPanel) continue;
        double& depth = zbuf[std::size_t(y) * kPanel + std::size_t(x)];
        if (z >= depth) continue;
        depth = z;
        canvas.blend(x + x_offset, y, c);
      }
  }
}

}  // namespace

Canvas closeup_picture(const SceneView& v, const std::vector<const HypothesisResult*>& hyps,
                       const ModelSamples& models, double diameter) {
  const auto top = std::find_if(hyps.begin(), hyps.end(), [](const auto* h) { return h->top; });
  Canvas canvas(2 * kPanel + 8, kPanel, {18, 18, 24});
  if (top == hyps.end()) return canvas;
  const HypothesisResult& h = **top;
  const double crop = 1.1 * diameter;  // scene points this near the detection are shown
  std::vector<Splat> splats;
  for (const auto& p : v.points)
    if (p.z() > 0 && (p.cast<double>() - h.row.t).norm() <= crop)
      splats.push_back({p.cast<double>() - h.row.t, kScenePoints, 0.0});
  if (const auto model = models.find(h.obj_id); model != models.end())
    for (const auto& m : model->second)
      splats.push_back({h.row.R * m.cast<double>(), kModelPoints, 0.03 * diameter});
  const double scale = 0.45 * kPanel / crop;
  const double radius_px = std::max(1.5, 0.012 * diameter * scale);
  draw_view(canvas, 0, splats, Eigen::Matrix3d::Identity(), scale, radius_px);
  // From 60 degrees aside: the camera rotated about the image's x axis, looking at the part.
  const Eigen::Matrix3d aside =
      Eigen::AngleAxisd(-std::numbers::pi / 3, Eigen::Vector3d::UnitX()).toRotationMatrix();
  draw_view(canvas, kPanel + 8, splats, aside, scale, radius_px);
  for (int y = 0; y < kPanel; ++y)
    for (int x = kPanel; x < kPanel + 8; ++x) canvas.blend(x, y, {90, 90, 100});
  return canvas;
}

}  // namespace binpick::eval
