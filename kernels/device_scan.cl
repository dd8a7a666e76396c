/* Exclusive prefix sum of n uints in three launches (used by the PPF table and voxel
 * subsampling; generic): each of `blocks` work items scans one chunk of `chunk` values
 * sequentially (a good fit for CPU devices), one work item scans the chunk totals, then every
 * value gets its chunk's offset. out has n + 1 values: out[n] is the total. */

__kernel void scan_chunks(__global const uint* in, const uint n, const uint chunk,
                          __global uint* out, __global uint* chunk_sums) {
  const uint b = get_global_id(0);
  const uint begin = b * chunk;
  if (begin >= n) {
    chunk_sums[b] = 0u;
    return;
  }
  const uint end = min(n, begin + chunk);
  uint sum = 0u;
  for (uint i = begin; i < end; ++i) {
    const uint v = in[i];
    out[i] = sum;
    sum += v;
  }
  chunk_sums[b] = sum;
}

/* chunk_sums[0..blocks) becomes exclusive; chunk_sums[blocks] and out[n] get the total. */
__kernel void scan_chunk_sums(__global uint* chunk_sums, const uint blocks, __global uint* out,
                              const uint n) {
  if (get_global_id(0) != 0) return;
  uint sum = 0u;
  for (uint b = 0; b < blocks; ++b) {
    const uint v = chunk_sums[b];
    chunk_sums[b] = sum;
    sum += v;
  }
  chunk_sums[blocks] = sum;
  out[n] = sum;
}

__kernel void scan_add_offsets(__global uint* out, const uint n, const uint chunk,
                               __global const uint* chunk_sums) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  out[i] += chunk_sums[i / chunk];
}
