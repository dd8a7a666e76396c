#version 450
// The projector's view of a rendered depth image, for the structured-light sensor model's
// shadows: every measurable pixel's surface, seen from the projector (a baseline along the
// camera's x), keeps the nearest depth per projector raster cell (atomicMin on the bits of
// positive floats, which order like the floats). A pixel splats the quad to its right and
// lower neighbours where they lie on its tangent plane (within edge_jump_mm), so a near
// surface leaves no holes for a far one to show through. stage 0 clears the raster to
// +infinity, stage 1 splats.
// C++ reference: projector_raster_reference (synth/sensor/sensor_reference.cpp); the push
// constants are SensorParams (synth/sensor/sensor_params.hpp).
layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer Depth { float depth[]; };
layout(std430, binding = 1) buffer Raster { uint raster[]; };  // float bits
layout(std430, binding = 2) readonly buffer Normals { float normals[]; };  // 3 a pixel

layout(push_constant) uniform Params {
  uint width, height, proj_width, proj_height;
  float fx, fy, cx, cy;
  float proj_scale, proj_offset_x, proj_fx_baseline, baseline_mm;
  float shadow_tolerance_mm, slope_factor, min_range_mm, max_range_mm;
  float cos_grazing, edge_jump_mm;
  int edge_radius;
  float noise_a_mm, noise_b_per_mm, added_sigma_mm;
  float quant_mm, quant_ref_mm;
  uint seed_lo, seed_hi;
  uint flags, stage;
  float cos_specular;
  float patch_inv_mm, patch_threshold;  // sensor_measure.comp's patches; unused here
} p;

const uint kInfinityBits = 0x7f800000u;
const int kMaxFootprint = 8;

bool measurable(float z) {
  return z > 0.0 && z <= 3.40282347e38 && z >= p.min_range_mm && z <= p.max_range_mm;
}

float projector_u(uint u, float z) {
  precise float a = p.proj_scale * (float(u) + 0.5);
  precise float b = p.proj_fx_baseline / z;
  precise float r = (a + p.proj_offset_x) - b;
  return r;
}

float projector_v(uint v) {
  precise float r = p.proj_scale * (float(v) + 0.5);
  return r;
}

// Whether depth zj at pixel q lies on the tangent plane of the surface point pt with normal
// n, within edge_jump_mm (as in sensor_measure.comp).
bool same_surface(vec3 pt, vec3 n, uvec2 q, float zj) {
  precise float dx = (float(q.x) - p.cx) / p.fx;
  precise float dy = (float(q.y) - p.cy) / p.fy;
  precise float num = (n.x * pt.x + n.y * pt.y) + n.z * pt.z;
  precise float den = (n.x * dx + n.y * dy) + n.z;
  if (den == 0.0) return false;
  precise float d = abs(zj - num / den);
  return d <= p.edge_jump_mm;
}

void main() {
  const uvec2 px = gl_GlobalInvocationID.xy;
  if (p.stage == 0u) {
    if (px.x < p.proj_width && px.y < p.proj_height) raster[px.y * p.proj_width + px.x] = kInfinityBits;
    return;
  }
  if (px.x >= p.width || px.y >= p.height) return;
  const uint i = px.y * p.width + px.x;
  const float z = depth[i];
  if (!measurable(z)) return;
  // The point and its normal as given, or facing the camera when that has no length.
  precise float rx = (float(px.x) - p.cx) / p.fx;
  precise float ry = (float(px.y) - p.cy) / p.fy;
  precise float x = rx * z, y = ry * z;
  const vec3 pt = vec3(x, y, z);
  const vec3 given = vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
  precise float len2 = (given.x * given.x + given.y * given.y) + given.z * given.z;
  const vec3 n = (len2 > 1e-24 && len2 <= 3.40282347e38) ? given : -pt;
  const float pu = projector_u(px.x, z), pv = projector_v(px.y);
  float lo_u = pu, hi_u = pu, lo_v = pv, hi_v = pv, nearest = z;
  const uvec2 steps[3] = uvec2[3](uvec2(1u, 0u), uvec2(0u, 1u), uvec2(1u, 1u));
  for (int k = 0; k < 3; ++k) {
    const uvec2 q = px + steps[k];
    if (q.x >= p.width || q.y >= p.height) continue;
    const float zj = depth[q.y * p.width + q.x];
    if (!measurable(zj) || !same_surface(pt, n, q, zj)) continue;
    const float qu = projector_u(q.x, zj), qv = projector_v(q.y);
    lo_u = min(lo_u, qu), hi_u = max(hi_u, qu);
    lo_v = min(lo_v, qv), hi_v = max(hi_v, qv);
    nearest = min(nearest, zj);
  }
  int x0 = int(floor(lo_u)), x1 = int(floor(hi_u));
  int y0 = int(floor(lo_v)), y1 = int(floor(hi_v));
  if (x1 - x0 >= kMaxFootprint || y1 - y0 >= kMaxFootprint) {  // stretched: the point only
    x0 = x1 = int(floor(pu));
    y0 = y1 = int(floor(pv));
    nearest = z;
  }
  x0 = max(x0, 0), y0 = max(y0, 0);
  x1 = min(x1, int(p.proj_width) - 1), y1 = min(y1, int(p.proj_height) - 1);
  const uint bits = floatBitsToUint(nearest);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) atomicMin(raster[uint(y) * p.proj_width + uint(x)], bits);
}
