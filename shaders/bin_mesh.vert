#version 450
// The meshes of a bin, one instanced draw per mesh (each kind of part, and the bin itself): the
// mesh per vertex, per instance its model-view matrix (3 rows, mm) and the id it writes (part
// index + 1 for a part, 0xffffffff for the bin, which is a surface but no part). Projection is
// the OpenCV/BOP pinhole, whose pixel centres are at integer (u, v), onto Vulkan's framebuffer,
// whose centres are at +0.5; the depth is the standard perspective one, near -> 0, far -> 1,
// which equation 1 of the paper inverts.
layout(location = 0) in vec3 position;  // part frame, mm
layout(location = 1) in vec3 normal;
layout(location = 2) in vec4 row0;      // per instance: part-to-camera rows
layout(location = 3) in vec4 row1;
layout(location = 4) in vec4 row2;
layout(location = 5) in uint instance_id;

layout(push_constant) uniform Camera {
  float width, height;  // of the viewport (the image)
  float fx, fy, cx, cy;
  float near_mm, far_mm;
} cam;

layout(location = 0) flat out uint part_id;  // part + 1 (0 is the background), or the bin
layout(location = 1) out vec3 camera_normal;

void main() {
  const vec4 p = vec4(position, 1.0);
  const vec3 c = vec3(dot(row0, p), dot(row1, p), dot(row2, p));
  camera_normal = vec3(dot(row0.xyz, normal), dot(row1.xyz, normal), dot(row2.xyz, normal));
  part_id = instance_id;
  // Clip w = z; framebuffer x = (x_clip / z + 1) width / 2 must be u + 0.5 = fx x / z + cx + 0.5
  // (y likewise: Vulkan's y points down like the image's).
  gl_Position = vec4(2.0 / cam.width * (cam.fx * c.x + (cam.cx + 0.5) * c.z) - c.z,
                     2.0 / cam.height * (cam.fy * c.y + (cam.cy + 0.5) * c.z) - c.z,
                     cam.far_mm * (c.z - cam.near_mm) / (cam.far_mm - cam.near_mm),
                     c.z);
}
