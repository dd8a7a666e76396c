#include "host/detect/scene/scene_prepare.hpp"

#include <algorithm>
#include <string>

#include "host/core/error.hpp"
#include "host/detect/scene/scene_lowpass.hpp"

namespace binpick {
namespace {

void check(DepthView depth, const bp_camera& cam, const ScenePrepOptions& opt) {
  check_depth_camera(depth, cam);
  check(opt.normals);
  check_lowpass_radius(opt.lowpass_radius);
}

// depth_to_points gives a point (w = 1) exactly where the raw depth is not 0.
std::size_t valid_pixels(DepthView depth) {
  return std::size_t(std::count_if(depth.raw.begin(), depth.raw.end(),
                                   [](std::uint16_t r) { return r != 0; }));
}

}  // namespace

PreparedScene prepare_scene(ocl::Device& dev, DepthView depth, const bp_camera& cam,
                            const ScenePrepOptions& opt) {
  check(depth, cam, opt);
  const std::size_t n = depth.raw.size();
  PreparedScene s;
  s.width = depth.width, s.height = depth.height, s.camera = cam;
  s.valid_pixels = valid_pixels(depth);
  Stopwatch clock;
  ocl::Buffer<std::uint16_t> raw(dev, std::span<const std::uint16_t>(depth.raw),
                                 CL_MEM_READ_ONLY);
  s.has_normals = opt.normals_everywhere;
  s.device = std::make_shared<DeviceScene>(
      DeviceScene{&dev, ocl::Buffer<float>(dev, 4 * n),
                  ocl::Buffer<float>(dev, s.has_normals ? 4 * n : 0), ocl::Buffer<float>(dev, n)});
  DeviceScene& d = *s.device;
  ocl::finish(dev);
  s.timings.push_back({"upload", clock.lap()});

  cl::Kernel to_points = dev.kernel("depth_to_points.cl", "depth_to_points");
  ocl::launch(dev, to_points, n, raw, cam, d.points);
  ocl::finish(dev);
  s.timings.push_back({"points", clock.lap()});

  if (s.has_normals) {
    enqueue_normals_from_points(dev, d.points, s.width, s.height, opt.normals, d.normals);
    ocl::finish(dev);
    s.timings.push_back({"normals", clock.lap()});
  }

  s.has_lowpass = opt.lowpass;
  if (s.has_lowpass) {
    enqueue_lowpass_depth(dev, d.points, s.width, s.height, opt.lowpass_radius, d.filtered);
    ocl::finish(dev);
    s.timings.push_back({"lowpass", clock.lap()});
  }

  if (opt.read_back) {
    s.points = {s.width, s.height, d.points.read(dev)};
    if (s.has_normals) s.normals = {s.width, s.height, d.normals.read(dev)};
    if (s.has_lowpass) s.filtered_depth = d.filtered.read(dev);
    s.timings.push_back({"readback", clock.lap()});
  }
  return s;
}

PreparedScene prepare_scene_reference(DepthView depth, const bp_camera& cam,
                                      const ScenePrepOptions& opt) {
  check(depth, cam, opt);
  PreparedScene s;
  s.width = depth.width, s.height = depth.height, s.camera = cam;
  s.valid_pixels = valid_pixels(depth);
  Stopwatch clock;
  s.points = depth_to_points_reference(depth, cam);
  s.timings.push_back({"points", clock.lap()});
  s.has_normals = opt.normals_everywhere;
  if (s.has_normals) {
    s.normals = normals_from_points_reference(s.points, opt.normals);
    s.timings.push_back({"normals", clock.lap()});
  }
  s.has_lowpass = opt.lowpass;
  if (s.has_lowpass) {
    s.filtered_depth = lowpass_depth_reference(s.points, opt.lowpass_radius);
    s.timings.push_back({"lowpass", clock.lap()});
  }
  return s;
}

}  // namespace binpick
