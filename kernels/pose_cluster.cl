/* Pose clustering (paper section III-B): which candidate poses are close enough
 * to be grouped, and how many votes each pose's neighbourhood holds.
 *
 * Poses are unit quaternions (x, y, z, w) and translations (mm). Poses i and j are compatible
 * when |t_i - t_j|^2 <= max_dist2 and |q_i . q_j| >= min_cos_half, i.e. the rotation between
 * them is at most the angle threshold (q and -q are the same rotation, hence the |.|). One work
 * item per pose i writes row i of the matrix and score[i] = the votes of all poses compatible
 * with it (itself included). The greedy grouping that uses them runs on the host
 * (host/detect/pose_cluster.cpp). The same float operations in the same order as
 * pose_compatible() there, so both give the same matrix bit for bit. */
#pragma OPENCL FP_CONTRACT OFF

__kernel void pose_compatibility(__global const float4* quats, __global const float4* trans,
                                 __global const uint* votes, const uint n, const float max_dist2,
                                 const float min_cos_half, __global uchar* compatible,
                                 __global uint* scores) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float4 qi = quats[i];
  const float4 ti = trans[i];
  uint score = 0u;
  for (uint j = 0; j < n; ++j) {
    const float4 qj = quats[j];
    const float4 tj = trans[j];
    const float dx = ti.x - tj.x, dy = ti.y - tj.y, dz = ti.z - tj.z;
    const float dist2 = dx * dx + dy * dy + dz * dz;
    const float dot = qi.x * qj.x + qi.y * qj.y + qi.z * qj.z + qi.w * qj.w;
    const uchar ok = dist2 <= max_dist2 && fabs(dot) >= min_cos_half;
    compatible[(size_t)i * n + j] = ok;
    if (ok) score += votes[j];
  }
  scores[i] = score;
}
