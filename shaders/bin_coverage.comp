#version 450
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
// Unoccluded pixel counts (BOP's px_count_all) from the part-id atlas in which every part was
// drawn alone into its own tile: each covered atlas pixel adds one to its part's count and
// grows its bounding box, mapped back to image pixels by the tile's shift.
// C++ reference: coverage_counts_reference (synth/render/bin_coverage.cpp).
layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer Atlas { uint atlas[]; };   // part + 1, 0 none
layout(std430, binding = 1) readonly buffer Shift { ivec2 shift[]; };  // image = atlas + shift
layout(std430, binding = 2) buffer Count { uint count[]; };
layout(std430, binding = 3) buffer Box { int box[]; };                 // min x, min y, max x, max y

layout(push_constant) uniform Params {
  uint width, height;  // of the atlas region read back
  uint instance_count;
} p;

// Lanes of a subgroup that see the same part combine before one of them does the atomics
// (as in bin_gbuffer.comp). part == 0xffffffff: none.
void count_pixel(uint part, ivec2 image) {
  while (true) {
    const uint first = subgroupBroadcastFirst(part);
    if (part == first) {
      const uint n = subgroupAdd(1u);
      const ivec2 lo = subgroupMin(image), hi = subgroupMax(image);
      if (part != 0xffffffffu && subgroupElect()) {
        atomicAdd(count[part], n);
        atomicMin(box[4 * part + 0], lo.x);
        atomicMin(box[4 * part + 1], lo.y);
        atomicMax(box[4 * part + 2], hi.x);
        atomicMax(box[4 * part + 3], hi.y);
      }
      break;
    }
  }
}

void main() {
  const uvec2 px = gl_GlobalInvocationID.xy;
  uint part = 0xffffffffu;
  ivec2 image = ivec2(0);
  if (px.x < p.width && px.y < p.height) {
    const uint id = atlas[px.y * p.width + px.x];
    if (id != 0u && id <= p.instance_count) {
      part = id - 1u;
      image = ivec2(px) + shift[part];
    }
  }
  count_pixel(part, image);  // in uniform control flow: every lane takes part
}
