/* The in-plane search of thin parts (host/detect/plane_search.hpp): the edge step of many poses.
 *
 * point_depths: one work item per pixel: the z of a point image (float4, w = 1 where there is
 * data), 0 where there is none. The search reads only the depth, at random pixels over the
 * part's footprint: a float a pixel is a quarter of the memory a float4 image is, and the
 * footprint of a part at 2 m in a 2064 x 1544 image then fits in a core's cache.
 *
 * edge_step_scores: one work item per pose (12 floats: R row-major, then t; model to camera).
 * For every `stride`-th edge probe (model frame, with the normal of the face it continues) that
 * faces the camera at the pose, the depth the sensor sees beyond the pose's edge, along the
 * probe's ray: the excess of the measured depth over the probe's, clamped to [.., tolerance];
 * no depth counts as a full tolerance (a shadow or a drop), something more than a tolerance in
 * front says nothing (the probe is skipped). The score is the mean over the probes counted, or
 * -1 with fewer than BP_EDGE_SEARCH_MIN_PROBES. A right pose of a sheet lying on a sheet scores
 * about its thickness; a pose shifted or turned in the sheet's plane has probes on the sheet
 * itself and scores less. Points with w = 1 are the part's own surface instead: their excess,
 * clamped to [0, tolerance] (the pose hanging over what the sensor sees), is averaged apart and
 * taken off, so that a pose lying off the sheet, over what lies beneath, does not score as if
 * its edges stepped down (also at least BP_EDGE_SEARCH_MIN_PROBES of them, or -1). No depth under
 * the part's own surface counts half a tolerance, as missing depth counts half in verification:
 * it may be the void beside a pile (the pose hangs over nothing) or the sensor's loss on real
 * surface, which on shiny sheet metal comes in patches (measured on plates under 29 %-valid
 * blob-shaped depth: as a full tolerance the search drew poses off the patches that have depth,
 * top-ranked right 16 of 32 images, strict 10; half: 19, strict 15, and paper bins of plates
 * one fewer of 28; none: 19, strict 15, but four fewer in the paper bins). Written out
 * identically in edge_step_scores_reference. */
#pragma OPENCL FP_CONTRACT OFF
#include "binpick_shared.h"

#define BP_EDGE_SEARCH_MIN_PROBES 10u

__kernel void point_depths(__global const float4* points, const uint n, __global float* depth) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float4 p = points[i];
  depth[i] = p.w != 0.0f ? p.z : 0.0f;
}

__kernel void edge_step_scores(__global const float* depth, const bp_camera cam,
                               __global const float4* probes, __global const float4* normals,
                               const uint n_probes, const uint stride,
                               __global const float* poses, const uint n_poses,
                               const float tolerance, __global float* scores) {
  const uint k = get_global_id(0);
  if (k >= n_poses) return;
  __global const float* P = poses + 12 * (size_t)k;
  float sum = 0.0f, own = 0.0f;
  uint count = 0u, own_count = 0u;
  for (uint j = 0; j < n_probes; j += stride) {
    const float4 q = probes[j];
    const float4 m = normals[j];
    const float x = P[0] * q.x + P[1] * q.y + P[2] * q.z + P[9];
    const float y = P[3] * q.x + P[4] * q.y + P[5] * q.z + P[10];
    const float z = P[6] * q.x + P[7] * q.y + P[8] * q.z + P[11];
    const float nx = P[0] * m.x + P[1] * m.y + P[2] * m.z;
    const float ny = P[3] * m.x + P[4] * m.y + P[5] * m.z;
    const float nz = P[6] * m.x + P[7] * m.y + P[8] * m.z;
    if (!(z > 0.0f) || nx * x + ny * y + nz * z >= 0.0f) continue;
    const float fu = floor(cam.fx * x / z + cam.cx + 0.5f);
    const float fv = floor(cam.fy * y / z + cam.cy + 0.5f);
    if (!(fu >= 0.0f && fv >= 0.0f && fu < (float)cam.width && fv < (float)cam.height)) continue;
    const float sz = depth[(size_t)fv * cam.width + (size_t)fu];
    float e = q.w != 0.0f ? 0.5f * tolerance : tolerance;  /* no depth: see the top */
    if (sz != 0.0f) {
      e = (sz - z) * (sqrt(x * x + y * y + z * z) / z);
      if (e < -tolerance) continue;
      e = fmin(e, tolerance);
    }
    if (q.w != 0.0f) {
      own += fmax(e, 0.0f);
      ++own_count;
    } else {
      sum += e;
      ++count;
    }
  }
  scores[k] = count >= BP_EDGE_SEARCH_MIN_PROBES && own_count >= BP_EDGE_SEARCH_MIN_PROBES
                  ? sum / (float)count - own / (float)own_count
                  : -1.0f;
}
