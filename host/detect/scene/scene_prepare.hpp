// Scene preparation of detection (paper section III-C): depth -> camera-frame
// points, normals and the low-pass filtered range image, all on the OpenCL device, kept there
// for the later stages (hypotheses, crops), optionally copied to the host.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/detect/scene/scene_normals.hpp"
#include "host/core/timing.hpp"
#include "host/detect/scene/depth_to_points.hpp"

namespace binpick {

struct ScenePrepOptions {
  NormalOptions normals;
  int lowpass_radius = 5;  // box (2r+1)^2 pixels of the low-pass range image
  // Normals of every pixel. The detector turns this off: it needs normals only at the points it
  // keeps around each hypothesis (scene_neighbourhood.hpp), and over the whole image they were
  // most of the preparation's time.
  bool normals_everywhere = true;
  // Copy points, normals and filtered depth to the host. Off, only PreparedScene::device holds
  // them (saves about 50 MB of copies for a 1600 x 900 image when later stages run on the device).
  bool read_back = true;
  // The low-pass range image. The detector turns this off when it applies a region
  // (bin_region.hpp), which writes the low-pass itself: over the kept points when it makes a
  // mask, over all of them when it does not.
  bool lowpass = true;
};

// The prepared scene on the device; every buffer is one entry per pixel, row-major.
struct DeviceScene {
  ocl::Device* dev = nullptr;   // the device the buffers live on
  ocl::Buffer<float> points;    // float4: xyz mm, w = 1 where there is data
  ocl::Buffer<float> normals;   // float4: unit normal, w = 1 where valid (empty without them)
  ocl::Buffer<float> filtered;  // low-pass depth in mm, 0 = no data
};

struct PreparedScene {
  std::uint32_t width = 0, height = 0;
  bp_camera camera{};
  PointImage points;                  // empty unless read back
  PointImage normals;                 // empty unless read back
  std::vector<float> filtered_depth;  // empty unless read back
  StageTimings timings;               // upload, points, normals, lowpass, readback
  bool has_normals = true;            // false: normals (device and host) were not computed
  bool has_lowpass = true;            // false: the filtered depth was not computed yet
  std::size_t valid_pixels = 0;       // pixels with data (w = 1)
  std::shared_ptr<DeviceScene> device;  // null for the reference
};

// Routine: the kernels depth_to_points, normals_from_points, lowpass_rows/cols in one queue.
// Throws InputError for a depth image that does not match the camera or bad options.
PreparedScene prepare_scene(ocl::Device& dev, DepthView depth, const bp_camera& cam,
                            const ScenePrepOptions& opt = {});
// Reference: the C++ references of the same stages (host vectors only, no device).
PreparedScene prepare_scene_reference(DepthView depth, const bp_camera& cam,
                                      const ScenePrepOptions& opt = {});

}  // namespace binpick
