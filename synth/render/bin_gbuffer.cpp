#include "synth/render/bin_gbuffer.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "host/core/error.hpp"
#include "synth/render/bin_noise.hpp"

namespace binpick {
namespace {

static_assert(sizeof(GBufferParams) == 48, "push constant block of bin_gbuffer.comp");
constexpr float kAmbient = 0.2f;

std::size_t pixels(const GBufferParams& p) { return std::size_t(p.width) * p.height; }

void check(const GBufferInput& in, const GBufferParams& p) {
  const std::size_t n = pixels(p);
  if (in.zbuffer.size() != n || in.ids.size() != n || in.raster_normals.size() != 4 * n)
    throw InputError("g-buffer input does not match " + std::to_string(p.width) + " x " +
                     std::to_string(p.height) + " pixels");
}

std::vector<std::uint8_t> narrow(const std::vector<std::uint32_t>& gray) {
  std::vector<std::uint8_t> out(gray.size());
  std::transform(gray.begin(), gray.end(), out.begin(), [](std::uint32_t g) { return std::uint8_t(g); });
  return out;
}

}  // namespace

GBufferParams gbuffer_params(const RenderCamera& c, double noise_sigma_mm, std::uint64_t seed,
                             std::uint32_t instance_count) {
  check_camera(c);
  if (!(noise_sigma_mm >= 0) || !std::isfinite(noise_sigma_mm))
    throw InputError("noise sigma must be finite and >= 0 mm");
  return {c.width, c.height, float(c.fx), float(c.fy), float(c.cx), float(c.cy),
          float(c.near_mm), float(c.far_mm), float(noise_sigma_mm),
          std::uint32_t(seed), std::uint32_t(seed >> 32), instance_count};
}

GBufferStage::GBufferStage(vkrt::Context& ctx, std::uint32_t width, std::uint32_t height)
    : ctx_(ctx),
      width_(width),
      height_(height),
      program_(ctx, "bin_gbuffer.comp", 10, sizeof(GBufferParams)),
      depth_(ctx, std::size_t(width) * height * sizeof(float)),
      points_(ctx, std::size_t(width) * height * 3 * sizeof(float)),
      normals_(ctx, std::size_t(width) * height * 3 * sizeof(float)),
      gray_(ctx, std::size_t(width) * height * sizeof(std::uint32_t)),
      instance_(ctx, std::size_t(width) * height * sizeof(std::int32_t)) {}

void GBufferStage::run(const vkrt::Buffer& zbuffer, const vkrt::Buffer& ids,
                       const vkrt::Buffer& raster_normals, const PartPixelBuffers& parts,
                       const GBufferParams& params) {
  if (params.width != width_ || params.height != height_)
    throw InputError("g-buffer stage made for " + std::to_string(width_) + " x " +
                     std::to_string(height_) + " pixels");
  program_.run({&zbuffer, &ids, &raster_normals, &depth_, &points_, &normals_, &gray_, &instance_,
                &parts.counts(), &parts.boxes()},
               &params, (width_ + 15) / 16, (height_ + 15) / 16);
}

GBufferOutput GBufferStage::read() const {
  GBufferOutput out;
  out.depth_mm = depth_.read<float>();
  out.points = points_.read<float>();
  out.normals = normals_.read<float>();
  out.gray = narrow(gray_.read<std::uint32_t>());
  out.instance = instance_.read<std::int32_t>();
  return out;
}

GBufferOutput bin_gbuffer(const GBufferInput& in, const GBufferParams& p) {
  check(in, p);
  auto& ctx = vkrt::Context::shared();
  GBufferStage stage(ctx, p.width, p.height);
  auto zbuffer = vkrt::Buffer::from(ctx, std::span<const float>(in.zbuffer));
  auto ids = vkrt::Buffer::from(ctx, std::span<const std::uint32_t>(in.ids));
  auto normals = vkrt::Buffer::from(ctx, std::span<const float>(in.raster_normals));
  PartPixelBuffers parts(ctx, p.instance_count);
  stage.run(zbuffer, ids, normals, parts, p);
  GBufferOutput out = stage.read();
  out.visible = parts.read();
  return out;
}

GBufferOutput bin_gbuffer_reference(const GBufferInput& in, const GBufferParams& p) {
  check(in, p);
  const std::size_t n = pixels(p);
  GBufferOutput out;
  out.depth_mm.assign(n, 0.0f);
  out.points.assign(3 * n, 0.0f);
  out.normals.assign(3 * n, 0.0f);
  out.gray.assign(n, 0);
  out.instance.assign(n, -1);
  out.visible = PartPixels(p.instance_count);
  const std::uint64_t seed = (std::uint64_t(p.seed_hi) << 32) | p.seed_lo;
  for (std::uint32_t v = 0; v < p.height; ++v)
    for (std::uint32_t u = 0; u < p.width; ++u) {
      const std::size_t i = std::size_t(v) * p.width + u;
      const std::uint32_t id = in.ids[i];
      const float b = in.zbuffer[i];
      const bool is_static = id == kStaticSurfaceId;
      if (id == 0 || (id > p.instance_count && !is_static) || !(b >= 0.0f && b < 1.0f)) continue;
      const float z = p.near_mm * p.far_mm / (p.far_mm + b * (p.near_mm - p.far_mm));
      const Eigen::Vector3f ray((float(u) - p.cx) / p.fx, (float(v) - p.cy) / p.fy, 1.0f);
      const Eigen::Vector3f to_camera = -ray.normalized();
      Eigen::Vector3f normal(in.raster_normals[4 * i], in.raster_normals[4 * i + 1],
                             in.raster_normals[4 * i + 2]);
      const float len = normal.norm();
      normal = len > 1e-12f ? Eigen::Vector3f(normal / len) : to_camera;
      if (normal.dot(to_camera) < 0.0f) normal = -normal;
      const float noisy_z =
          p.noise_sigma_mm > 0.0f
              ? std::max(z + p.noise_sigma_mm * pixel_gaussian(seed, std::uint32_t(i)), 1e-3f * z)
              : z;
      const Eigen::Vector3f point = ray * noisy_z;
      out.depth_mm[i] = noisy_z;
      for (int k = 0; k < 3; ++k) {
        out.points[3 * i + k] = point[k];
        out.normals[3 * i + k] = normal[k];
      }
      const float intensity = kAmbient + (1.0f - kAmbient) * std::max(normal.dot(to_camera), 0.0f);
      out.gray[i] = std::uint8_t(std::min(std::floor(255.0f * intensity + 0.5f), 255.0f));
      if (is_static) continue;  // a surface, but no part's
      out.instance[i] = std::int32_t(id) - 1;
      out.visible.add(id - 1, int(u), int(v));
    }
  return out;
}

}  // namespace binpick
