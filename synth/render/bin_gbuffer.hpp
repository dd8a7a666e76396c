// The compute pass after the raster pass (shaders/bin_gbuffer.comp): from the z-buffer, the
// part-id attachment and the normal attachment to what the sensor delivers (depth in mm with
// optional noise, points, normals, intensity, part index) and per part its visible pixels.
#pragma once

#include <cstdint>
#include <vector>

#include "synth/render/bin_camera.hpp"
#include "synth/render/part_pixels.hpp"
#include "host/runtime/vk/vk_buffer.hpp"
#include "host/runtime/vk/vk_compute.hpp"

namespace binpick {

// The push constant block of bin_gbuffer.comp.
struct GBufferParams {
  std::uint32_t width = 0, height = 0;
  float fx = 0, fy = 0, cx = 0, cy = 0, near_mm = 0, far_mm = 0;
  float noise_sigma_mm = 0;         // Gaussian along the viewing ray; 0: none
  std::uint32_t seed_lo = 0, seed_hi = 0;
  std::uint32_t instance_count = 0;  // ids above it are treated as background
};
GBufferParams gbuffer_params(const RenderCamera& camera, double noise_sigma_mm, std::uint64_t seed,
                             std::uint32_t instance_count);

// The id of a surface that belongs to no part (the bin): shaded, instance -1, counted for none.
inline constexpr std::uint32_t kStaticSurfaceId = 0xffffffffu;

// The attachments as read back: a pixel is a surface where 0 <= zbuffer < 1 and
// 1 <= id <= instance_count (id = part + 1, 0 = background) or id = kStaticSurfaceId.
struct GBufferInput {
  std::vector<float> zbuffer;          // 1 a pixel, row-major
  std::vector<std::uint32_t> ids;      // 1 a pixel
  std::vector<float> raster_normals;   // 4 a pixel: interpolated camera-frame normal, any length
};

struct GBufferOutput {
  std::vector<float> depth_mm;          // z, 0 where no surface
  std::vector<float> points;            // 3 a pixel, mm
  std::vector<float> normals;           // 3 a pixel, unit, towards the camera
  std::vector<std::uint8_t> gray;       // 0.2 ambient + 0.8 Lambert, light at the camera; 0 none
  std::vector<std::int32_t> instance;   // part index, -1 none
  PartPixels visible;                   // per part: pixels where it is seen
};

// The shader with its output buffers, reused from render to render.
class GBufferStage {
 public:
  GBufferStage(vkrt::Context& ctx, std::uint32_t width, std::uint32_t height);
  // Inputs are device buffers laid out as in GBufferInput; `parts` accumulates the visible
  // pixel counts and boxes (it must hold params.instance_count parts).
  void run(const vkrt::Buffer& zbuffer, const vkrt::Buffer& ids, const vkrt::Buffer& raster_normals,
           const PartPixelBuffers& parts, const GBufferParams& params);
  // The images of the last run (`visible` is left empty: read it from the PartPixelBuffers).
  GBufferOutput read() const;

 private:
  vkrt::Context& ctx_;
  std::uint32_t width_, height_;
  vkrt::ComputeProgram program_;
  vkrt::Buffer depth_, points_, normals_, gray_, instance_;
};

// Routine: bin_gbuffer.comp on the shared Vulkan device (with fresh buffers).
GBufferOutput bin_gbuffer(const GBufferInput& input, const GBufferParams& params);
// Reference: the same in plain C++ (float arithmetic, as in the shader).
GBufferOutput bin_gbuffer_reference(const GBufferInput& input, const GBufferParams& params);

}  // namespace binpick
