// The structured-light sensor model on the Vulkan device: sensor_projector.comp (clear, then
// splat the projector raster) and sensor_measure.comp (per pixel: shadow, grazing, edge,
// range, noise, quantisation). C++ reference: synth/sensor/sensor_reference.hpp.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "host/runtime/vk/vk_buffer.hpp"
#include "host/runtime/vk/vk_compute.hpp"
#include "synth/sensor/sensor_images.hpp"
#include "synth/sensor/sensor_params.hpp"

namespace binpick {

// The two shaders with their buffers for one image size, reused from image to image (building
// it compiles the pipelines: keep one for a series of bins).
class SensorStage {
 public:
  SensorStage(vkrt::Context& ctx, std::uint32_t width, std::uint32_t height);
  // Runs both shaders on `in` (checked against params) and reads the result back.
  SensorOutput run(const SensorImages& in, const SensorParams& params);
  // The projector raster of the last run (proj_width x proj_height, +infinity where empty);
  // empty if that run had no shadows.
  std::vector<float> raster() const;

 private:
  vkrt::Context& ctx_;
  std::uint32_t width_, height_;
  vkrt::ComputeProgram projector_, measure_;
  vkrt::Buffer depth_, normals_, gray_, depth_out_, points_out_, normals_out_, gray_out_, dropout_;
  std::optional<vkrt::Buffer> raster_;  // sized by the last run's parameters
  bool raster_filled_ = false;
};

// Routine: the sensor model on the shared Vulkan device, with a fresh stage.
SensorOutput sensor_model(const SensorImages& in, const SensorParams& params);
// Reference: the same in plain C++.
SensorOutput sensor_model_reference(const SensorImages& in, const SensorParams& params);

}  // namespace binpick
