#include "synth/sensor/sensor_stage.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "host/core/error.hpp"
#include "synth/sensor/sensor_reference.hpp"

namespace binpick {
namespace {

std::uint32_t groups(std::uint32_t n) { return (n + 15) / 16; }

}  // namespace

SensorStage::SensorStage(vkrt::Context& ctx, std::uint32_t width, std::uint32_t height)
    : ctx_(ctx),
      width_(width),
      height_(height),
      projector_(ctx, "sensor_projector.comp", 3, sizeof(SensorParams)),
      measure_(ctx, "sensor_measure.comp", 9, sizeof(SensorParams)),
      depth_(ctx, std::size_t(width) * height * sizeof(float)),
      normals_(ctx, std::size_t(width) * height * 3 * sizeof(float)),
      gray_(ctx, std::size_t(width) * height * sizeof(std::uint32_t)),
      depth_out_(ctx, std::size_t(width) * height * sizeof(float)),
      points_out_(ctx, std::size_t(width) * height * 3 * sizeof(float)),
      normals_out_(ctx, std::size_t(width) * height * 3 * sizeof(float)),
      gray_out_(ctx, std::size_t(width) * height * sizeof(std::uint32_t)),
      dropout_(ctx, std::size_t(width) * height * sizeof(std::uint32_t)) {}

SensorOutput SensorStage::run(const SensorImages& in, const SensorParams& params) {
  if (params.width != width_ || params.height != height_)
    throw InputError("sensor stage made for " + std::to_string(width_) + " x " +
                     std::to_string(height_) + " pixels");
  check_sensor_images(in, params);
  const std::size_t n = std::size_t(width_) * height_;
  const std::size_t cells = std::size_t(params.proj_width) * params.proj_height;
  if (!raster_ || raster_->size() != cells * sizeof(std::uint32_t))
    raster_.emplace(ctx_, cells * sizeof(std::uint32_t));
  std::memcpy(depth_.mapped(), in.depth_mm.data(), n * sizeof(float));
  std::memcpy(normals_.mapped(), in.normals.data(), 3 * n * sizeof(float));
  auto* gray = static_cast<std::uint32_t*>(gray_.mapped());
  std::copy(in.gray.begin(), in.gray.end(), gray);

  SensorParams p = params;
  raster_filled_ = (p.flags & kSensorShadows) != 0;
  if (raster_filled_) {
    p.stage = 0;
    projector_.run({&depth_, &*raster_, &normals_}, &p, groups(p.proj_width), groups(p.proj_height));
    p.stage = 1;
    projector_.run({&depth_, &*raster_, &normals_}, &p, groups(p.width), groups(p.height));
  }
  measure_.run({&depth_, &normals_, &gray_, &*raster_, &depth_out_, &points_out_,
                &normals_out_, &gray_out_, &dropout_},
               &p, groups(p.width), groups(p.height));

  SensorOutput out;
  out.depth_mm = depth_out_.read<float>();
  out.points = points_out_.read<float>();
  out.normals = normals_out_.read<float>();
  const auto gray_out = gray_out_.read<std::uint32_t>();
  const auto dropout = dropout_.read<std::uint32_t>();
  out.gray.resize(n);
  out.dropout.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.gray[i] = std::uint8_t(gray_out[i]);
    out.dropout[i] = std::uint8_t(dropout[i]);
  }
  return out;
}

std::vector<float> SensorStage::raster() const {
  if (!raster_filled_) return {};
  return raster_->read<float>();
}

SensorOutput sensor_model(const SensorImages& in, const SensorParams& params) {
  check_sensor_images(in, params);
  return SensorStage(vkrt::Context::shared(), params.width, params.height).run(in, params);
}

SensorOutput sensor_model_reference(const SensorImages& in, const SensorParams& params) {
  return sensor_measure_reference(in, projector_raster_reference(in, params), params);
}

}  // namespace binpick
