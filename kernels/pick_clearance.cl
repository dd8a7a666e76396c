/* Pick planning's collision test: work item g takes candidate g (a gripper at one grasp of one
 * detection) and reads the points of its pixel window, counting those deeper than the tolerance
 * inside the gripper and keeping the least distance to it of those on its side of the grasp
 * point (pick_shared.h). Candidates are independent tasks of very different windows. */
#pragma OPENCL FP_CONTRACT OFF
#include "pick_shared.h"

__kernel void pick_clearance(__global const float4* points, const uint width,
                             __global const bp_pick_candidate* candidates, const uint count,
                             __global bp_pick_result* results) {
  const uint g = get_global_id(0);
  if (g >= count) return;
  const bp_pick_candidate c = candidates[g];
  uint colliding = 0;
  float clearance = c.cap;
  for (uint v = c.rect[1]; v < c.rect[3]; ++v)
    for (uint u = c.rect[0]; u < c.rect[2]; ++u) {
      const float4 p = points[v * width + u];
      if (p.w == 0.0f) continue;
      float qz;
      const float d = bp_pick_distance(&c, p.x, p.y, p.z, &qz);
      if (d < -c.tolerance)
        ++colliding;
      else if (qz < -c.tolerance && d < clearance)
        clearance = d > 0.0f ? d : 0.0f;
    }
  results[g].colliding = colliding;
  results[g].clearance = clearance;
}
