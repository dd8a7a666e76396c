/* Depth image (uint16, depth_mm = raw * depth_scale) to camera-frame points in mm.
 * A pixel with no data (raw 0) gives w = 0; a valid one w = 1. */
#include "binpick_shared.h"

__kernel void depth_to_points(__global const ushort* depth, const bp_camera cam,
                              __global float4* points) {
  const uint i = get_global_id(0);
  if (i >= cam.width * cam.height) return;
  const ushort raw = depth[i];
  if (raw == 0) {
    points[i] = (float4)(0.0f, 0.0f, 0.0f, 0.0f);
    return;
  }
  const float u = (float)(i % cam.width);
  const float v = (float)(i / cam.width);
  const float z = (float)raw * cam.depth_scale;
  points[i] = (float4)((u - cam.cx) * z / cam.fx, (v - cam.cy) * z / cam.fy, z, 1.0f);
}
