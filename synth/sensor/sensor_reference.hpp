// The structured-light sensor model in plain C++: the reference of the two compute shaders
// (sensor_projector.comp, sensor_measure.comp), float arithmetic in the shaders' order.
#pragma once

#include <vector>

#include "synth/sensor/sensor_images.hpp"
#include "synth/sensor/sensor_params.hpp"

namespace binpick {

// Throws InputError unless the images have params.width x params.height pixels.
void check_sensor_images(const SensorImages& in, const SensorParams& p);

// The projector raster (sensor_projector.comp): per cell the nearest depth splatted into it,
// +infinity where none (size proj_width x proj_height; one cell when shadows are off).
std::vector<float> projector_raster_reference(const SensorImages& in, const SensorParams& p);

// The measured images (sensor_measure.comp) given that raster.
SensorOutput sensor_measure_reference(const SensorImages& in, const std::vector<float>& raster,
                                      const SensorParams& p);

}  // namespace binpick
