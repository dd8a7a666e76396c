#include <string>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/core/error.hpp"
#include "host/detect/scene/depth_to_points.hpp"

namespace binpick {

void check_depth_camera(DepthView depth, const bp_camera& cam) {
  if (depth.width != cam.width || depth.height != cam.height ||
      depth.raw.size() != std::size_t(depth.width) * depth.height)
    throw InputError("depth image of " + std::to_string(depth.width) + " x " +
                     std::to_string(depth.height) + " does not match the camera's " +
                     std::to_string(cam.width) + " x " + std::to_string(cam.height));
  if (!(cam.fx > 0 && cam.fy > 0 && cam.depth_scale > 0))
    throw InputError("camera focal lengths and depth_scale must be positive");
}

PointImage depth_to_points(ocl::Device& dev, DepthView depth, const bp_camera& cam) {
  check_depth_camera(depth, cam);
  const std::size_t n = depth.raw.size();
  ocl::Buffer<std::uint16_t> in(dev, std::span<const std::uint16_t>(depth.raw), CL_MEM_READ_ONLY);
  ocl::Buffer<float> out(dev, 4 * n, CL_MEM_WRITE_ONLY);  // float4 per pixel
  cl::Kernel k = dev.kernel("depth_to_points.cl", "depth_to_points");
  ocl::launch(dev, k, n, in, cam, out);
  return {depth.width, depth.height, out.read(dev)};
}

PointImage depth_to_points_reference(DepthView depth, const bp_camera& cam) {
  check_depth_camera(depth, cam);
  PointImage img{depth.width, depth.height, std::vector<float>(4 * depth.raw.size(), 0.0f)};
  for (std::uint32_t v = 0; v < depth.height; ++v)
    for (std::uint32_t u = 0; u < depth.width; ++u) {
      const std::size_t i = std::size_t(v) * depth.width + u;
      if (depth.raw[i] == 0) continue;
      const float z = float(depth.raw[i]) * cam.depth_scale;
      img.xyzw[4 * i + 0] = (float(u) - cam.cx) * z / cam.fx;
      img.xyzw[4 * i + 1] = (float(v) - cam.cy) * z / cam.fy;
      img.xyzw[4 * i + 2] = z;
      img.xyzw[4 * i + 3] = 1.0f;
    }
  return img;
}

}  // namespace binpick
