#version 450
// The scene pass: part id and interpolated camera-frame normal; depth comes from the z-buffer.
layout(location = 0) flat in uint part_id;
layout(location = 1) in vec3 camera_normal;

layout(location = 0) out uint out_id;
layout(location = 1) out vec4 out_normal;

void main() {
  out_id = part_id;
  out_normal = vec4(camera_normal, 0.0);
}
