#include "tests/support/rendered_parts.hpp"

#include <cmath>
#include <cstdint>

#include "host/app/options/model_options.hpp"
#include "host/train/surface_sampling.hpp"

namespace binpick::test {

RenderedScene render_parts(const std::vector<std::pair<Mesh, Eigen::Isometry3f>>& parts,
                           float floor_z) {
  RenderedScene s;
  const std::uint32_t w = 320, h = 240;
  s.cam = {600.0f, 600.0f, (w - 1) / 2.0f, (h - 1) / 2.0f, 0.1f, w, h, 0};
  std::vector<float> z(w * h, floor_z);
  std::vector<Eigen::Vector3f> point(w * h), normal(w * h);
  std::vector<bool> owned(w * h, false);
  for (const auto& [mesh, T] : parts) {
    const PointCloud samples = sample_surface(mesh, 300000);
    for (std::size_t i = 0; i < samples.points.size(); ++i) {
      const Eigen::Vector3f p = T * samples.points[i];
      const long u = std::lround(s.cam.fx * p.x() / p.z() + s.cam.cx);
      const long v = std::lround(s.cam.fy * p.y() / p.z() + s.cam.cy);
      if (u < 0 || v < 0 || u >= long(w) || v >= long(h) || p.z() >= z[v * w + u]) continue;
      z[v * w + u] = p.z();
      point[v * w + u] = p;
      normal[v * w + u] = T.linear() * samples.normals[i];
      owned[v * w + u] = true;
    }
  }
  s.depth = {w, h, std::vector<std::uint16_t>(w * h)};
  for (std::size_t k = 0; k < z.size(); ++k) {
    s.depth.raw[k] = std::uint16_t(std::lround(z[k] / s.cam.depth_scale));
    if (!owned[k]) continue;
    s.cloud.points.push_back(point[k]);
    s.cloud.normals.push_back(normal[k]);
  }
  return s;
}

ShaftBeside shaft_beside(const Eigen::Vector3f& at, const Mesh& other,
                         const Eigen::Isometry3f& other_pose) {
  ShaftBeside s;
  s.part = cli::load_part({"builtin:shaft", {}});
  s.model = train_ppf_model(s.part.mesh, {});
  s.pose = Eigen::Isometry3f::Identity();
  s.pose.linear() = Eigen::AngleAxisf(0.3f, Eigen::Vector3f(0.2f, 0.5f, 0.8f).normalized())
                        .toRotationMatrix();
  s.pose.translation() = at;
  s.scene = render_parts({{s.part.mesh, s.pose}, {other, other_pose}}, 600.0f + s.model.diameter);
  return s;
}

eval::PoseError ShaftBeside::error_of(const Detection& d) const {
  return eval::symmetric_pose_error(pose.linear().cast<double>(), pose.translation().cast<double>(),
                                    d.R, d.t, part.symmetries);
}

}  // namespace binpick::test
