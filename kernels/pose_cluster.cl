/* Pose clustering (paper section III-B): which candidate poses are close enough
 * to be grouped, and how many votes each pose's neighbourhood holds.
 *
 * Poses are unit quaternions (x, y, z, w) and translations (mm). Poses i and j are compatible
 * when |t_i - t_j|^2 <= max_dist2 and their rotations are within the angle threshold up to the
 * part's symmetries (pose_cluster_shared.h; without symmetries |q_i . q_j| >= min_cos_half:
 * q and -q are the same rotation, hence the |.|). `axes` holds the posed symmetry axis R_i a of
 * each pose in the axis modes (unused otherwise), `symmetries` the discrete symmetry rotations
 * without the identity. One work item per pose i writes row i of the matrix and score[i] = the
 * votes of all poses compatible with it (itself included). The greedy grouping that uses them
 * runs on the host (host/detect/cluster/pose_cluster.cpp). The same float operations in the same order
 * as the reference there, so both give the same matrix bit for bit. */
#pragma OPENCL FP_CONTRACT OFF

#include "binpick_shared.h"
#include "pose_cluster_shared.h"

static inline bp_quat bp_quat_of(const float4 v) {
  bp_quat q;
  q.x = v.x;
  q.y = v.y;
  q.z = v.z;
  q.w = v.w;
  return q;
}

__kernel void pose_compatibility(__global const float4* quats, __global const float4* trans,
                                 __global const float4* axes, __global const uint* votes,
                                 const uint n, const float max_dist2, const float min_cos_half,
                                 const uint mode, __global const float4* symmetries,
                                 const uint symmetry_count, const float min_cos_axis,
                                 __global uchar* compatible, __global uint* scores) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const bp_quat qi = bp_quat_of(quats[i]);
  const float4 ti = trans[i];
  const float4 ai = axes[mode == BP_CLUSTER_AXIS || mode == BP_CLUSTER_AXIS_EITHER ? i : 0];
  uint score = 0u;
  for (uint j = 0; j < n; ++j) {
    const float4 tj = trans[j];
    const float dx = ti.x - tj.x, dy = ti.y - tj.y, dz = ti.z - tj.z;
    const float dist2 = dx * dx + dy * dy + dz * dz;
    uchar ok = dist2 <= max_dist2;
    if (ok && mode == BP_CLUSTER_ROTATIONS) {
      const bp_quat qj = bp_quat_of(quats[j]);
      ok = fabs(bp_quat_dot(qi, qj)) >= min_cos_half;
      if (!ok && symmetry_count > 0u) {
        const bp_quat r = bp_quat_relative(qi, qj);
        for (uint k = 0; k < symmetry_count && !ok; ++k)
          ok = fabs(bp_quat_dot(r, bp_quat_of(symmetries[k]))) >= min_cos_half;
      }
    } else if (ok && mode != BP_CLUSTER_ANY) {
      const float4 aj = axes[j];
      ok = bp_cluster_axes_close(ai.x * aj.x + ai.y * aj.y + ai.z * aj.z, mode, min_cos_axis);
    }
    compatible[(size_t)i * n + j] = ok;
    if (ok) score += votes[j];
  }
  scores[i] = score;
}
