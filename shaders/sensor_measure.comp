#version 450
// The structured-light sensor model, one invocation a pixel: what the sensor measures at a
// rendered pixel given the projector raster of sensor_projector.comp. A pixel has no depth
// out of the scanning range, in a projector shadow (farther than the nearest surface the
// projector sees there, beyond a tolerance), at a grazing angle to the camera or the
// projector, in a specular highlight (optional), near a depth jump, or in a patch of lost
// depth (optional); otherwise its depth gets axial noise a + b z^2 and is quantised. Shadows
// are dark in the gray image; nothing else changes it.
// C++ reference: sensor_measure_reference (synth/sensor/sensor_reference.cpp), operation for
// operation; the noise hash repeats synth/render/bin_noise.hpp word for word, the patches'
// field synth/sensor/sensor_patches.hpp.
layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer Depth { float depth[]; };
layout(std430, binding = 1) readonly buffer Normals { float normals[]; };  // 3 a pixel
layout(std430, binding = 2) readonly buffer Gray { uint gray[]; };
layout(std430, binding = 3) readonly buffer Raster { uint raster[]; };     // float bits
layout(std430, binding = 4) writeonly buffer DepthOut { float depth_out[]; };
layout(std430, binding = 5) writeonly buffer PointsOut { float points_out[]; };    // 3 a pixel
layout(std430, binding = 6) writeonly buffer NormalsOut { float normals_out[]; };  // 3 a pixel
layout(std430, binding = 7) writeonly buffer GrayOut { uint gray_out[]; };
layout(std430, binding = 8) writeonly buffer DropoutOut { uint dropout_out[]; };

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
  float patch_inv_mm, patch_threshold;
} p;

const uint kSensorEffects = 1u, kSensorShadows = 2u, kSensorPatches = 4u, kShadowGray = 51u;
const uint kValid = 0u, kNoSurface = 1u, kOutOfRange = 2u, kShadow = 3u, kGrazing = 4u,
           kSpecular = 5u, kEdge = 6u, kPatch = 7u;

uint pcg_hash(uint x) {
  const uint state = x * 747796405u + 2891336453u;
  const uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

float pixel_gaussian(uint pixel) {
  const uint key = pcg_hash(p.seed_lo ^ pcg_hash(p.seed_hi));
  const uint h1 = pcg_hash(pixel ^ key), h2 = pcg_hash(h1);
  const float u1 = float((h1 >> 8) + 1u) * 5.9604645e-08;
  const float u2 = float(h2 >> 8) * 5.9604645e-08;
  return sqrt(-2.0 * log(u1)) * cos(6.2831853 * u2);
}

bool has_surface(float z) { return z > 0.0 && z <= 3.40282347e38; }
bool in_range(float z) { return z >= p.min_range_mm && z <= p.max_range_mm; }
bool measurable(float z) { return has_surface(z) && in_range(z); }

// A pixel's surface point: its ray (z component 1), the point and its normal as given, or
// facing the camera (-point) when that has no length or is not finite.
struct Surfel {
  uvec2 px;
  float z, rx, ry;
  vec3 pt, n;
};

Surfel surfel(uvec2 px) {
  Surfel s;
  const uint i = px.y * p.width + px.x;
  s.px = px;
  s.z = depth[i];
  precise float rx = (float(px.x) - p.cx) / p.fx;
  precise float ry = (float(px.y) - p.cy) / p.fy;
  precise float x = rx * s.z, y = ry * s.z;
  s.rx = rx, s.ry = ry;
  s.pt = vec3(x, y, s.z);
  const vec3 n = vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
  precise float len2 = (n.x * n.x + n.y * n.y) + n.z * n.z;
  s.n = (len2 > 1e-24 && len2 <= 3.40282347e38) ? n : -s.pt;
  return s;
}

// Whether depth zj at pixel q lies on s's tangent plane, within edge_jump_mm: a steep surface
// is not a discontinuity, a step is.
bool same_surface(Surfel s, ivec2 q, float zj) {
  precise float dx = (float(q.x) - p.cx) / p.fx;
  precise float dy = (float(q.y) - p.cy) / p.fy;
  precise float num = (s.n.x * s.pt.x + s.n.y * s.pt.y) + s.n.z * s.pt.z;
  precise float den = (s.n.x * dx + s.n.y * dy) + s.n.z;
  if (den == 0.0) return false;  // the neighbour's ray runs along the plane
  precise float d = abs(zj - num / den);
  return d <= p.edge_jump_mm;  // false for NaN
}

// The largest depth change to a neighbour (3 x 3) on the same surface.
float local_slope(Surfel s) {
  float slope = 0.0;
  for (int dv = -1; dv <= 1; ++dv)
    for (int du = -1; du <= 1; ++du) {
      const ivec2 q = ivec2(s.px) + ivec2(du, dv);
      if (q.x < 0 || q.y < 0 || q.x >= int(p.width) || q.y >= int(p.height)) continue;
      const float zj = depth[uint(q.y) * p.width + uint(q.x)];
      if (!measurable(zj) || !same_surface(s, q, zj)) continue;
      precise float d = abs(zj - s.z);
      slope = max(slope, d);
    }
  return slope;
}

bool shadowed(Surfel s) {
  precise float tolerance = p.shadow_tolerance_mm + p.slope_factor * local_slope(s);
  precise float a = p.proj_scale * (float(s.px.x) + 0.5);
  precise float b = p.proj_fx_baseline / s.z;
  precise float pu = (a + p.proj_offset_x) - b;
  precise float pv = p.proj_scale * (float(s.px.y) + 0.5);
  const float x = floor(pu), y = floor(pv);
  if (!(x >= 0.0 && y >= 0.0 && x < float(p.proj_width) && y < float(p.proj_height))) return true;
  const float nearest = uintBitsToFloat(raster[uint(y) * p.proj_width + uint(x)]);
  precise float behind = s.z - nearest;
  return behind > tolerance;
}

vec3 unit_normal(Surfel s) {
  precise float len = sqrt((s.n.x * s.n.x + s.n.y * s.n.y) + s.n.z * s.n.z);
  precise vec3 n = vec3(s.n.x / len, s.n.y / len, s.n.z / len);
  return n;
}

bool grazing(Surfel s) {
  const vec3 n = unit_normal(s), pt = s.pt;
  precise float plen = sqrt((pt.x * pt.x + pt.y * pt.y) + pt.z * pt.z);
  precise float cos_camera = -((n.x * pt.x + n.y * pt.y) + n.z * pt.z) / plen;
  precise float tx = p.baseline_mm - pt.x, ty = -pt.y, tz = -pt.z;
  precise float tlen = sqrt((tx * tx + ty * ty) + tz * tz);
  precise float cos_projector = ((n.x * tx + n.y * ty) + n.z * tz) / tlen;
  return cos_camera < p.cos_grazing || cos_projector < p.cos_grazing;
}

// Whether the normal lies within the specular cone around the bisector of the unit rays to
// the camera and to the projector.
bool specular(Surfel s) {
  const vec3 n = unit_normal(s), pt = s.pt;
  precise float plen = sqrt((pt.x * pt.x + pt.y * pt.y) + pt.z * pt.z);
  precise float tx = p.baseline_mm - pt.x, ty = -pt.y, tz = -pt.z;
  precise float tlen = sqrt((tx * tx + ty * ty) + tz * tz);
  precise float hx = -pt.x / plen + tx / tlen, hy = -pt.y / plen + ty / tlen,
                hz = -pt.z / plen + tz / tlen;
  precise float hlen = sqrt((hx * hx + hy * hy) + hz * hz);
  precise float cos_half = ((n.x * hx + n.y * hy) + n.z * hz) / hlen;
  return cos_half > p.cos_specular;
}

bool near_edge(Surfel s) {
  const int r = p.edge_radius;
  for (int dv = -r; dv <= r; ++dv)
    for (int du = -r; du <= r; ++du) {
      const ivec2 q = ivec2(s.px) + ivec2(du, dv);
      if (q.x < 0 || q.y < 0 || q.x >= int(p.width) || q.y >= int(p.height)) continue;
      const float zj = depth[uint(q.y) * p.width + uint(q.x)];
      if (!has_surface(zj) || !same_surface(s, q, zj)) return true;
    }
  return false;
}

// The patches' field, synth/sensor/sensor_patches.hpp line for line.
float patch_lattice(uint key, int x, int y, int z) {
  uint h = pcg_hash(uint(x) ^ key);
  h = pcg_hash(h ^ uint(y));
  h = pcg_hash(h ^ uint(z));
  return float(h >> 8) * 5.9604645e-08;
}

float patch_weight(float f) {
  precise float a = 3.0 - 2.0 * f;
  precise float w = (f * f) * a;
  return w;
}

float patch_lerp(float a, float b, float w) {
  precise float r = a + w * (b - a);
  return r;
}

float patch_value_noise(uint key, float x, float y, float z) {
  const float x0 = floor(x), y0 = floor(y), z0 = floor(z);
  const int ix = int(x0), iy = int(y0), iz = int(z0);
  precise float fx = x - x0, fy = y - y0, fz = z - z0;
  const float wx = patch_weight(fx), wy = patch_weight(fy), wz = patch_weight(fz);
  float c[2][2];
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      c[k][j] = patch_lerp(patch_lattice(key, ix, iy + j, iz + k),
                           patch_lattice(key, ix + 1, iy + j, iz + k), wx);
  return patch_lerp(patch_lerp(c[0][0], c[0][1], wy), patch_lerp(c[1][0], c[1][1], wy), wz);
}

const float kPatchRotation[9] = float[9](
    0.599884033203125, -0.5937347412109375, 0.5363006591796875,
    0.7526092529296875, 0.646209716796875, -0.12640380859375,
    -0.271514892578125, 0.4794464111328125, 0.834503173828125);

float patch_field(float px, float py, float pz) {
  const uint key = pcg_hash(p.seed_lo ^ pcg_hash(p.seed_hi ^ 0x243f6a88u));
  precise float qx = px * p.patch_inv_mm, qy = py * p.patch_inv_mm, qz = pz * p.patch_inv_mm;
  const float r[9] = kPatchRotation;
  precise float x = (r[0] * qx + r[1] * qy) + r[2] * qz;
  precise float y = (r[3] * qx + r[4] * qy) + r[5] * qz;
  precise float z = (r[6] * qx + r[7] * qy) + r[8] * qz;
  const float coarse = patch_value_noise(key, x, y, z);
  precise float x2 = 2.0 * x + 0.5, y2 = 2.0 * y + 0.5, z2 = 2.0 * z + 0.5;
  const float fine = patch_value_noise(pcg_hash(key ^ 0x85a308d3u), x2, y2, z2);
  precise float field = coarse + 0.5 * fine;
  return field;
}

// Whether the pixel lies in a patch without depth: the field at its (ideal) point.
bool in_patch(Surfel s) { return patch_field(s.pt.x, s.pt.y, s.pt.z) < p.patch_threshold; }

// Noise along the ray, then quantisation.
float measured_depth(uint i, float z) {
  precise float axial = p.noise_a_mm + p.noise_b_per_mm * (z * z);
  precise float sigma = sqrt(axial * axial + p.added_sigma_mm * p.added_sigma_mm);
  precise float out_z = z;
  if (sigma > 0.0) {
    precise float g = pixel_gaussian(i);
    precise float noisy = z + sigma * g;
    precise float floor_z = 1e-3 * z;
    out_z = max(noisy, floor_z);
  }
  if (p.quant_mm > 0.0) {
    if (p.quant_ref_mm > 0.0) {  // a lattice in disparity: steps grow with z^2
      precise float c = (p.quant_ref_mm * p.quant_ref_mm) / p.quant_mm;
      precise float k = max(floor(c / out_z + 0.5), 1.0);
      out_z = c / k;
    } else {
      precise float k = max(floor(out_z / p.quant_mm + 0.5), 1.0);
      out_z = k * p.quant_mm;
    }
  }
  return out_z;
}

void main() {
  const uvec2 px = gl_GlobalInvocationID.xy;
  if (px.x >= p.width || px.y >= p.height) return;
  const uint i = px.y * p.width + px.x;
  const Surfel s = surfel(px);
  const float z = s.z;
  const bool effects = (p.flags & kSensorEffects) != 0u;
  uint why = kValid;
  if (!has_surface(z)) why = kNoSurface;
  else if (!effects) why = kValid;
  else if (!in_range(z)) why = kOutOfRange;
  else if ((p.flags & kSensorShadows) != 0u && shadowed(s)) why = kShadow;
  else if (grazing(s)) why = kGrazing;
  else if (specular(s)) why = kSpecular;
  else if (near_edge(s)) why = kEdge;
  else if ((p.flags & kSensorPatches) != 0u && in_patch(s)) why = kPatch;
  dropout_out[i] = why;
  gray_out[i] = why == kShadow ? kShadowGray : gray[i];
  if (why != kValid) {
    depth_out[i] = 0.0;
    for (uint k = 0u; k < 3u; ++k) {
      points_out[3 * i + k] = 0.0;
      normals_out[3 * i + k] = 0.0;
    }
    return;
  }
  const float measured = effects ? measured_depth(i, z) : z;
  // Ideal: the normal as given (the images stay as rendered); otherwise the unit normal.
  const vec3 n = effects ? unit_normal(s)
                         : vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
  precise float x = s.rx * measured, y = s.ry * measured;
  depth_out[i] = measured;
  points_out[3 * i] = x;
  points_out[3 * i + 1] = y;
  points_out[3 * i + 2] = measured;
  for (uint k = 0u; k < 3u; ++k) normals_out[3 * i + k] = n[k];
}
