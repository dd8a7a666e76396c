#version 450
// The z-buffer of a perspective render to camera-frame points in mm (paper, equation 1):
// z = dn df / (df + b (dn - df)), x = (u - cx) z / fx, y = (v - cy) z / fy.
// b = 1 (the far plane, where the clear value survives) means no surface: the point is all 0.
layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer ZBuffer { float zbuffer[]; };
layout(std430, binding = 1) writeonly buffer Points { vec4 points[]; };

layout(push_constant) uniform Params {
  uint width;
  uint height;
  float fx, fy, cx, cy;
  float near_mm, far_mm;
} p;

void main() {
  const uvec2 px = gl_GlobalInvocationID.xy;
  if (px.x >= p.width || px.y >= p.height) return;
  const uint i = px.y * p.width + px.x;
  const float b = zbuffer[i];
  if (!(b < 1.0) || !(b >= 0.0)) {
    points[i] = vec4(0.0);
    return;
  }
  const float z = p.near_mm * p.far_mm / (p.far_mm + b * (p.near_mm - p.far_mm));
  points[i] = vec4((float(px.x) - p.cx) * z / p.fx, (float(px.y) - p.cy) * z / p.fy, z, 1.0);
}
