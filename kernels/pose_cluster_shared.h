/* Pose clustering's rotation test with the part's symmetries (kernels/pose_cluster.cl and its
 * C++ reference, host/detect/cluster/pose_cluster.cpp), shared so that both compute the same float
 * operations in the same order. Valid OpenCL C 1.2 and C++20; include after binpick_shared.h.
 *
 * Poses i and j (unit quaternions q, model to scene) are the same rotation up to a symmetry
 * when, by mode:
 *   BP_CLUSTER_ROTATIONS   |q_i . q_j| >= cos(angle / 2), or |(q_j^-1 q_i) . g| >= cos(angle / 2)
 *                          for one of the part's discrete symmetry rotations g (model frame):
 *                          the angle of R_j^T R_i, or of R_j^T R_i against g, within the angle;
 *   BP_CLUSTER_AXIS        the part is round about the axis a (model frame): the posed axes
 *                          u = R a satisfy u_i . u_j >= cos(angle), the turn about a is free;
 *   BP_CLUSTER_AXIS_EITHER and a half turn swaps its ends: |u_i . u_j| >= cos(angle);
 *   BP_CLUSTER_ANY         round about two axes (a sphere): every rotation is the same.
 * Translations are compared elsewhere, at the posed model centroid, which every symmetry of
 * the part keeps in place. */
#ifndef BINPICK_POSE_CLUSTER_SHARED_H
#define BINPICK_POSE_CLUSTER_SHARED_H

#define BP_CLUSTER_ROTATIONS 0u
#define BP_CLUSTER_AXIS 1u
#define BP_CLUSTER_AXIS_EITHER 2u
#define BP_CLUSTER_ANY 3u

/* Discrete symmetry rotations the kernel takes, the identity not counted: with it, 64, which
 * holds the largest finite rotation group of a solid (the icosahedron's 60). */
#define BP_CLUSTER_MAX_SYMMETRIES 63u

/* A quaternion (x, y, z, w); the layout of a float4. */
typedef struct {
  float x, y, z, w;
} bp_quat;

BP_FN float bp_quat_dot(bp_quat a, bp_quat b) {
  return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
}

/* b^-1 a = conj(b) a for unit quaternions: the rotation R_b^T R_a. */
BP_FN bp_quat bp_quat_relative(bp_quat a, bp_quat b) {
  bp_quat r;
  r.x = b.w * a.x - a.w * b.x - b.y * a.z + b.z * a.y;
  r.y = b.w * a.y - a.w * b.y - b.z * a.x + b.x * a.z;
  r.z = b.w * a.z - a.w * b.z - b.x * a.y + b.y * a.x;
  r.w = b.w * a.w + b.x * a.x + b.y * a.y + b.z * a.z;
  return r;
}

/* The axis modes: whether posed axes with this dot product are within the angle. */
BP_FN int bp_cluster_axes_close(float dot, bp_u32 mode, float min_cos_axis) {
  if (mode == BP_CLUSTER_AXIS_EITHER && dot < 0.0f) dot = -dot;
  return dot >= min_cos_axis;
}

#endif
