#include "synth/render/zbuffer_to_points.hpp"

#include <string>

#include "host/core/error.hpp"
#include "host/runtime/vk/vk_compute.hpp"

namespace binpick {
namespace {

void check(const std::vector<float>& zbuffer, const ZBufferCamera& cam) {
  if (zbuffer.size() != std::size_t(cam.width) * cam.height)
    throw InputError("z-buffer of " + std::to_string(zbuffer.size()) + " values does not match " +
                     std::to_string(cam.width) + " x " + std::to_string(cam.height));
  if (!(cam.fx > 0 && cam.fy > 0 && cam.near_mm > 0 && cam.far_mm > cam.near_mm))
    throw InputError("z-buffer camera needs positive focal lengths and 0 < near < far");
}

}  // namespace

std::vector<float> zbuffer_to_points(const std::vector<float>& zbuffer, const ZBufferCamera& cam) {
  check(zbuffer, cam);
  auto& ctx = vkrt::Context::shared();
  static_assert(sizeof(ZBufferCamera) == 32, "push constant block of zbuffer_to_points.comp");
  auto in = vkrt::Buffer::from(ctx, std::span<const float>(zbuffer));
  vkrt::Buffer out(ctx, zbuffer.size() * 4 * sizeof(float));
  vkrt::ComputeProgram program(ctx, "zbuffer_to_points.comp", 2, sizeof(ZBufferCamera));
  program.run({&in, &out}, &cam, (cam.width + 15) / 16, (cam.height + 15) / 16);
  return out.read<float>();
}

std::vector<float> zbuffer_to_points_reference(const std::vector<float>& zbuffer,
                                               const ZBufferCamera& cam) {
  check(zbuffer, cam);
  std::vector<float> out(4 * zbuffer.size(), 0.0f);
  for (std::uint32_t v = 0; v < cam.height; ++v)
    for (std::uint32_t u = 0; u < cam.width; ++u) {
      const std::size_t i = std::size_t(v) * cam.width + u;
      const float b = zbuffer[i];
      if (!(b < 1.0f) || !(b >= 0.0f)) continue;
      const float z = cam.near_mm * cam.far_mm / (cam.far_mm + b * (cam.near_mm - cam.far_mm));
      out[4 * i + 0] = (float(u) - cam.cx) * z / cam.fx;
      out[4 * i + 1] = (float(v) - cam.cy) * z / cam.fy;
      out[4 * i + 2] = z;
      out[4 * i + 3] = 1.0f;
    }
  return out;
}

}  // namespace binpick
