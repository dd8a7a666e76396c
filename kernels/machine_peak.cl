/* What the device can do at best: plain kernels each bound by one resource, so that every
 * detection stage's throughput can be reported as a fraction of it (
 * bench/lib/machine_peak.cpp times them, tests/bench/test_machine_peak.cpp checks them against
 * plain C++ with the same arithmetic).
 *
 * peak_stream_triad  memory bandwidth: STREAM's triad a = b + s c over float4.
 * peak_fma           floating point: independent chains of FMAs, nothing from memory.
 * peak_int_ops       32-bit integer ALU (hashing and vote counting are integer work).
 * peak_gather        random 4-byte loads from a table at hashed indices, like the model's hash
 *                    table and the vote accumulators of ppf_vote: lookups per second.
 *
 * Every kernel writes a result per work item that depends on all of its work, so the compiler
 * cannot drop any of it, and guards its tail (the host rounds the global size up to a whole
 * work group). The chain shapes (8 chains of 16 lanes) are repeated in
 * bench/lib/machine_peak.hpp (kPeakFmaLanes, kPeakIntLanes) and in the C++ references. */
#pragma OPENCL FP_CONTRACT OFF /* only the explicit fma()s fuse: the C++ reference matches bit for bit */

/* a = b + s c, element i a float4. n = elements. fma() rather than b + s * c so that the
 * rounding is fixed (one rounding, as std::fma) whatever the compiler contracts. PoCL runs it as
 * one 128-bit load-fma-store per work item (the tail guard keeps it from vectorising across
 * work items); unguarded, clamped, 16-elements-a-work-item and grid-stride variants were no
 * faster: the loop is bound by memory, not instructions. Ordinary stores, so a is also read
 * (write-allocate), which STREAM's byte count leaves out. */
__kernel void peak_stream_triad(__global float4* a, __global const float4* b,
                                __global const float4* c, const float s, const uint n) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  a[i] = fma((float4)(s), c[i], b[i]);
}

/* 8 independent float16 chains acc = acc * mul + add, `iterations` steps each:
 * 8 x 16 = 128 FMAs a step. Why this shape: PoCL does not vectorise such a kernel across work
 * items, so the vector type is the SIMD width: float16 is one AVX-512 register (float8 ran at
 * half the rate, float4 at a quarter), and 8 chains cover the FMA latency of two pipes (12 were
 * no faster). Written out, not as an array, so every accumulator stays in a register.
 * Chain k, lane l starts at x + 16 k + l with x = (i mod 1024) / 1024, all exact in float.
 * out[i] = the sum of all 128 lanes, in the order written below. With 0 < mul < 1 the chains
 * converge to add / (1 - mul) and never reach infinities or denormals. */
__kernel void peak_fma(__global float* out, const uint n, const uint iterations, const float mul,
                       const float add) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float16 m = (float16)(mul), a = (float16)(add);
  const float16 x = (float16)((float)(i & 1023u) * (1.0f / 1024.0f)) +
                    (float16)(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f, 8.0f, 9.0f, 10.0f,
                              11.0f, 12.0f, 13.0f, 14.0f, 15.0f);
  float16 c0 = x, c1 = x + 16.0f, c2 = x + 32.0f, c3 = x + 48.0f;
  float16 c4 = x + 64.0f, c5 = x + 80.0f, c6 = x + 96.0f, c7 = x + 112.0f;
  for (uint t = 0; t < iterations; ++t) {
    c0 = fma(c0, m, a);
    c1 = fma(c1, m, a);
    c2 = fma(c2, m, a);
    c3 = fma(c3, m, a);
    c4 = fma(c4, m, a);
    c5 = fma(c5, m, a);
    c6 = fma(c6, m, a);
    c7 = fma(c7, m, a);
  }
  const float16 s = ((c0 + c1) + (c2 + c3)) + ((c4 + c5) + (c6 + c7));
  const float8 h = s.lo + s.hi;
  const float4 q = h.lo + h.hi;
  const float2 d = q.lo + q.hi;
  out[i] = d.x + d.y;
}

/* 8 independent uint16 chains acc = (acc ^ x) + y: 2 integer operations per lane
 * a step, 256 a step in all (uint16 for the same reason as float16 above). Chain k, lane l
 * starts at 128 i + 16 k + l (mod 2^32). out[i] = the wrapping sum of all 128 lanes
 * (order-free, so exact on both sides). */
__kernel void peak_int_ops(__global uint* out, const uint n, const uint iterations, const uint x,
                           const uint y) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint16 vx = (uint16)(x), vy = (uint16)(y);
  const uint16 base = (uint16)(128u * i) + (uint16)(0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 10u,
                                                    11u, 12u, 13u, 14u, 15u);
  uint16 c0 = base, c1 = base + 16u, c2 = base + 32u, c3 = base + 48u;
  uint16 c4 = base + 64u, c5 = base + 80u, c6 = base + 96u, c7 = base + 112u;
  for (uint t = 0; t < iterations; ++t) {
    c0 = (c0 ^ vx) + vy;
    c1 = (c1 ^ vx) + vy;
    c2 = (c2 ^ vx) + vy;
    c3 = (c3 ^ vx) + vy;
    c4 = (c4 ^ vx) + vy;
    c5 = (c5 ^ vx) + vy;
    c6 = (c6 ^ vx) + vy;
    c7 = (c7 ^ vx) + vy;
  }
  const uint16 s = ((c0 + c1) + (c2 + c3)) + ((c4 + c5) + (c6 + c7));
  const uint8 h = s.lo + s.hi;
  const uint4 q = h.lo + h.hi;
  const uint2 d = q.lo + q.hi;
  out[i] = d.x + d.y;
}

/* A cheap integer mix with good avalanche (Wellons' "lowbias32"): consecutive keys land on
 * unrelated table slots, so neither the prefetcher nor the cache lines help. */
static inline uint peak_hash(uint v) {
  v ^= v >> 16;
  v *= 0x7feb352du;
  v ^= v >> 15;
  v *= 0x846ca68bu;
  v ^= v >> 16;
  return v;
}

/* Work item i makes `lookups` loads table[hash(i * lookups + seed + k) scaled to size] and
 * writes their wrapping sum. The index is floor(hash * size / 2^32): any table size, no
 * division; written as a 64-bit product because PoCL's mul_hi(uint, uint) is emulated with
 * four 16-bit products (it made the in-cache gather 3 times slower). The loads are independent
 * of each other (as the voting's are), so this measures how many random loads the memory
 * system keeps in flight, not one load's latency. */
__kernel void peak_gather(__global const uint* table, const uint size, const uint n,
                          const uint lookups, const uint seed, __global uint* out) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint key = i * lookups + seed;
  uint sum = 0u;
  for (uint k = 0; k < lookups; ++k) sum += table[(uint)(((ulong)peak_hash(key + k) * size) >> 32)];
  out[i] = sum;
}
