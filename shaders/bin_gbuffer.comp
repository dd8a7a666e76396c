#version 450
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
// The rendered attachments of a bin to what the sensor delivers, one invocation a pixel:
// z-buffer -> depth (paper, equation 1) with optional Gaussian noise along the viewing ray,
// camera-frame points, unit normals facing the camera, Lambert intensity with the light at the
// camera, the part index, and per part its visible pixel count and bounding box (atomics).
// Id 0xffffffff is a surface that is no part (the bin): shaded, instance -1, counted for none.
// C++ reference: bin_gbuffer_reference (synth/render/bin_gbuffer.cpp); the noise hash repeats
// synth/render/bin_noise.hpp word for word.
layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer ZBuffer { float zbuffer[]; };
layout(std430, binding = 1) readonly buffer Ids { uint ids[]; };          // part + 1, 0 none, or kStatic
layout(std430, binding = 2) readonly buffer RasterNormals { vec4 raster_normals[]; };
layout(std430, binding = 3) writeonly buffer Depth { float depth[]; };
layout(std430, binding = 4) writeonly buffer Points { float points[]; };    // 3 a pixel
layout(std430, binding = 5) writeonly buffer Normals { float normals[]; };  // 3 a pixel
layout(std430, binding = 6) writeonly buffer Gray { uint gray[]; };
layout(std430, binding = 7) writeonly buffer Instance { int instance[]; };
layout(std430, binding = 8) buffer VisibleCount { uint visible_count[]; };
layout(std430, binding = 9) buffer VisibleBox { int visible_box[]; };     // min x, min y, max x, max y

layout(push_constant) uniform Params {
  uint width, height;
  float fx, fy, cx, cy, near_mm, far_mm;
  float noise_sigma_mm;
  uint seed_lo, seed_hi;
  uint instance_count;
} p;

const float kAmbient = 0.2;
const uint kStatic = 0xffffffffu;

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

void write_empty(uint i) {
  depth[i] = 0.0;
  for (uint k = 0; k < 3; ++k) {
    points[3 * i + k] = 0.0;
    normals[3 * i + k] = 0.0;
  }
  gray[i] = 0u;
  instance[i] = -1;
}

// Writes pixel i's outputs; false when it shows no surface.
bool shade(uint i, uvec2 px) {
  const uint id = ids[i];
  const float b = zbuffer[i];
  if (id == 0u || (id > p.instance_count && id != kStatic) || !(b >= 0.0 && b < 1.0)) return false;
  const float z = p.near_mm * p.far_mm / (p.far_mm + b * (p.near_mm - p.far_mm));
  const vec3 ray = vec3((float(px.x) - p.cx) / p.fx, (float(px.y) - p.cy) / p.fy, 1.0);
  const vec3 to_camera = -normalize(ray);

  // The interpolated vertex normal, unit and turned towards the camera.
  vec3 n = raster_normals[i].xyz;
  const float len = length(n);
  n = len > 1e-12 ? n / len : to_camera;
  if (dot(n, to_camera) < 0.0) n = -n;

  // Noise moves the point along its ray; it never crosses the camera.
  const float noisy_z = p.noise_sigma_mm > 0.0
                            ? max(z + p.noise_sigma_mm * pixel_gaussian(i), 1e-3 * z)
                            : z;
  const vec3 point = ray * noisy_z;
  depth[i] = noisy_z;
  for (uint k = 0; k < 3; ++k) {
    points[3 * i + k] = point[k];
    normals[3 * i + k] = n[k];
  }
  const float intensity = kAmbient + (1.0 - kAmbient) * max(dot(n, to_camera), 0.0);
  gray[i] = uint(min(floor(255.0 * intensity + 0.5), 255.0));
  instance[i] = id == kStatic ? -1 : int(id) - 1;
  return true;
}

// Adds this pixel to its part's count and box. Atomics on a few hundred counters from every
// pixel contend: lanes of a subgroup that see the same part (most, as parts are ~100 pixels
// wide) first combine, then one of them does the atomics. part == 0xffffffff: none.
void count_pixel(uint part, ivec2 px) {
  while (true) {
    const uint first = subgroupBroadcastFirst(part);
    if (part == first) {
      const uint n = subgroupAdd(1u);
      const ivec2 lo = subgroupMin(px), hi = subgroupMax(px);
      if (part != 0xffffffffu && subgroupElect()) {
        atomicAdd(visible_count[part], n);
        atomicMin(visible_box[4 * part + 0], lo.x);
        atomicMin(visible_box[4 * part + 1], lo.y);
        atomicMax(visible_box[4 * part + 2], hi.x);
        atomicMax(visible_box[4 * part + 3], hi.y);
      }
      break;
    }
  }
}

void main() {
  const uvec2 px = gl_GlobalInvocationID.xy;
  uint part = 0xffffffffu;
  if (px.x < p.width && px.y < p.height) {
    const uint i = px.y * p.width + px.x;
    if (shade(i, px)) part = ids[i] == kStatic ? 0xffffffffu : ids[i] - 1u;
    else write_empty(i);
  }
  count_pixel(part, ivec2(px));  // in uniform control flow: every lane takes part
}
