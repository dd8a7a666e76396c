#version 450
// The coverage pass (each part alone in its atlas tile): only which part covers the pixel.
layout(location = 0) flat in uint part_id;
layout(location = 1) in vec3 camera_normal;  // unused; declared so the interfaces match

layout(location = 0) out uint out_id;

void main() { out_id = part_id; }
