/* Voxel subsampling: one point per occupied voxel, the one nearest the voxel's centre (ties:
 * the lower index), so the result does not depend on the order in which work items run.
 * Voxels are counted from `origin` (the cloud's minimum corner) in a dense grid of
 * dims.x * dims.y * dims.z cells. Four passes: best distance per voxel (atomic_min on the bits
 * of a non-negative float, which order like the floats), best index among the points at that
 * distance, keep flags, then compaction after a prefix sum of the flags (device_scan.cl), which
 * keeps the survivors in input order.
 *
 * Thin walls (the model): a wall thinner than a voxel has two faces in it, and keeping only the
 * point nearest the centre keeps one face (for a sheet lying along a voxel layer, the same face
 * everywhere), so the other cannot be recognised. With faces, a second round keeps, per voxel,
 * the point nearest the centre among those whose normal points away from the first winner's
 * (dot product < 0): voxel_opposite_side marks them, the same two passes pick the winner among
 * them (their cells offset by the number of cells, so one buffer holds both rounds), and
 * voxel_keep_flags keeps the winners of both rounds.
 *
 * No contraction into fused multiply-adds: the C++ reference must compute the same bits. */
#pragma OPENCL FP_CONTRACT OFF

__kernel void voxel_best_distance(__global const float4* points, const uint n, const float4 origin,
                                  const float inv_voxel, const uint4 dims, __global uint* cell_of,
                                  __global uint* dist_bits, __global uint* best_dist) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float4 f = (points[i] - origin) * inv_voxel; /* position in voxel units */
  const uint cx = min((uint)floor(f.x), dims.x - 1u);
  const uint cy = min((uint)floor(f.y), dims.y - 1u);
  const uint cz = min((uint)floor(f.z), dims.z - 1u);
  const float dx = f.x - ((float)cx + 0.5f);
  const float dy = f.y - ((float)cy + 0.5f);
  const float dz = f.z - ((float)cz + 0.5f);
  const uint cell = (cz * dims.y + cy) * dims.x + cx;
  const uint bits = as_uint(dx * dx + dy * dy + dz * dz);
  cell_of[i] = cell;
  dist_bits[i] = bits;
  atomic_min(&best_dist[cell], bits);
}

__kernel void voxel_best_index(__global const uint* cell_of, __global const uint* dist_bits,
                               const uint n, __global const uint* best_dist,
                               __global uint* best_index) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint cell = cell_of[i];
  if (dist_bits[i] == best_dist[cell]) atomic_min(&best_index[cell], i);
}

__kernel void voxel_keep_flags(__global const uint* cell_of, const uint n,
                               __global const uint* best_index, __global uint* keep) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  keep[i] = best_index[cell_of[i]] == i ? 1u : 0u;
}

/* Second round of the faces mode: a point whose normal points away from its voxel's first
 * winner moves to cell + cells (the opposite face's slot) and competes there; the others get
 * the cell 0xffffffff (no slot). dist_bits stay as computed. */
__kernel void voxel_opposite_side(__global const float4* normals, __global const uint* cell_of,
                                  const uint n, const uint cells, __global const uint* best_index,
                                  __global uint* cell2_of, __global uint* best_dist,
                                  __global const uint* dist_bits) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint cell = cell_of[i];
  const float4 a = normals[i], b = normals[best_index[cell]];
  const bool opposite = a.x * b.x + a.y * b.y + a.z * b.z < 0.0f;
  cell2_of[i] = opposite ? cell + cells : 0xffffffffu;
  if (opposite) atomic_min(&best_dist[cell + cells], dist_bits[i]);
}

__kernel void voxel_best_index_opposite(__global const uint* cell2_of,
                                        __global const uint* dist_bits, const uint n,
                                        __global const uint* best_dist,
                                        __global uint* best_index) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint cell = cell2_of[i];
  if (cell != 0xffffffffu && dist_bits[i] == best_dist[cell]) atomic_min(&best_index[cell], i);
}

__kernel void voxel_keep_flags_faces(__global const uint* cell_of, const uint n, const uint cells,
                                     __global const uint* best_index, __global uint* keep) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint cell = cell_of[i];
  keep[i] = best_index[cell] == i || best_index[cell + cells] == i ? 1u : 0u;
}

__kernel void voxel_compact(__global const uint* keep, __global const uint* position,
                            const uint n, __global uint* kept_index) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  if (keep[i]) kept_index[position[i]] = i;
}
