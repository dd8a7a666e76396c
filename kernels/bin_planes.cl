/* RANSAC plane scoring of the bin fit (host/detect/bin_planes.cpp): for each candidate plane,
 * the number of sample points within tol of it. One work item per plane scans every point, so
 * the counts are exact integers whatever the scheduling. */
#pragma OPENCL FP_CONTRACT OFF
#include "scene_mask_shared.h"

__kernel void bin_plane_inliers(__global const float4* points, const uint n,
                                __global const bp_plane* planes, const uint count,
                                const float tol, __global uint* inliers) {
  const uint k = get_global_id(0);
  if (k >= count) return;
  const bp_plane pl = planes[k];
  uint c = 0;
  for (uint i = 0; i < n; ++i) {
    const float4 p = points[i];
    c += bp_plane_distance(&pl, p.x, p.y, p.z) <= tol ? 1u : 0u;
  }
  inliers[k] = c;
}
