/* Types and discretisation shared by the OpenCL C kernels and the C++ host and references, so
 * that a kernel and its reference cannot drift apart. Valid OpenCL C 1.2 and valid C++20.
 * Structs hold only 4-byte scalars, so their layout is the same on both sides. */
#ifndef BINPICK_SHARED_H
#define BINPICK_SHARED_H

#ifdef __OPENCL_VERSION__
#define BP_FN static inline __attribute__((always_inline))
/* Fetch the cache line at p ahead of its use. OpenCL's prefetch() does nothing on PoCL; Clang's
 * builtin becomes the CPU's prefetch instruction. For reads scattered over an image larger than
 * the caches, where each would otherwise stall the work item on memory. */
#ifdef __clang__
#define BP_PREFETCH(p) __builtin_prefetch(p)
#else
#define BP_PREFETCH(p) ((void)(p))
#endif
typedef uint bp_u32;
typedef int bp_i32;
#define BP_FLOOR floor
#else
#include <cmath>
#include <cstdint>
#define BP_FN inline
typedef std::uint32_t bp_u32;
typedef std::int32_t bp_i32;
#define BP_FLOOR std::floor
#endif

/* Pinhole camera, OpenCV/BOP convention: pixel (u, v) has its centre at integer coordinates,
 * x = (u - cx) z / fx, y = (v - cy) z / fy, z forward, y down. depth_mm = raw * depth_scale. */
typedef struct {
  float fx, fy, cx, cy;
  float depth_scale;
  bp_u32 width, height;
  bp_u32 reserved;
} bp_camera;

/* Point pair feature discretisation (Drost 2010; paper section IV): the distance in
 * n_dist steps up to max_distance (the diameter), the three feature angles in [0, pi] and alpha
 * in [-pi, pi) in steps of angle_step (2 pi / 30: 12 degrees). */
typedef struct {
  float max_distance;
  float dist_step;
  float angle_step;
  bp_u32 n_dist;       /* distance bins */
  bp_u32 n_angle;      /* bins of a feature angle in [0, pi] */
  bp_u32 n_alpha;      /* bins of alpha in [-pi, pi) */
  bp_u32 reserved[2];
} bp_ppf_quant;

#define BP_PPF_DEFAULT_DIST_STEPS 20
#define BP_PPF_DEFAULT_ANGLE_STEPS 30
#define BP_PI_F 3.14159265358979323846f

/* The bin of value in steps of `step`, clamped to [0, bins - 1]; NaN goes to bin 0.
 * The clamp keeps values at the top edge (an angle of exactly pi) in range. */
BP_FN bp_u32 bp_quantize(float value, float step, bp_u32 bins) {
  float q = BP_FLOOR(value / step);
  if (!(q >= 0.0f)) return 0u;
  if (q >= (float)bins) return bins - 1u;
  return (bp_u32)q;
}

/* One hash key per discretised feature: (d, a1, a2, a3) in mixed radix. */
BP_FN bp_u32 bp_ppf_key(bp_u32 d, bp_u32 a1, bp_u32 a2, bp_u32 a3, bp_u32 n_angle) {
  return ((d * n_angle + a1) * n_angle + a2) * n_angle + a3;
}

BP_FN bp_u32 bp_ppf_key_count(bp_ppf_quant q) { return q.n_dist * q.n_angle * q.n_angle * q.n_angle; }

/* ---- PPF model: table entries, skipped pairs, alpha ------------------------------ */

/* One hash table entry: the model reference point m_r of a pair and its alpha_m in [-pi, pi). */
typedef struct {
  bp_u32 point;
  float alpha;
} bp_ppf_entry;

/* A table entry as the vote reads it (ppf_vote.cl): the first accumulator cell of m_r's row
 * (m_r * n_alpha) and 1.5 n_alpha - alpha_m n_alpha / (2 pi). Worked out once at upload, so the
 * hot loop is an add, a truncation and two compares per vote instead of a subtraction, two
 * multiplications and an add (bp_vote_bin). */
typedef struct {
  bp_u32 row;
  float offset;
} bp_vote_entry;

BP_FN float bp_vote_offset(float alpha_m, float inv_step, bp_u32 n_alpha) {
  return 1.5f * (float)n_alpha - alpha_m * inv_step;
}

/* The alpha bin of alpha_s - alpha_m wrapped into [0, n_alpha), with scaled_s = alpha_s inv_step
 * (inv_step = n_alpha / (2 pi)). scaled_s + offset is in (n / 2, 5 n / 2) for alphas in
 * [-pi, pi], where truncation is floor and two compares wrap it: no division. *frac is the
 * part past the bin's start (alpha spreading votes for the neighbour on the nearer side). */
BP_FN bp_u32 bp_vote_bin(float scaled_s, float offset, bp_u32 n_alpha, float* frac) {
  const float u = scaled_s + offset;
  const bp_u32 t = (bp_u32)u;
  *frac = u - (float)t;
  bp_u32 b = t;
  if (b >= 2u * n_alpha) b -= 2u * n_alpha;
  else if (b >= n_alpha) b -= n_alpha;
  return b;
}

/* The bin next to b on the side frac lies nearer. */
BP_FN bp_u32 bp_vote_neighbour(bp_u32 b, float frac, bp_u32 n_alpha) {
  if (frac < 0.5f) return b == 0u ? n_alpha - 1u : b - 1u;
  return b + 1u == n_alpha ? 0u : b + 1u;
}

/* The key of a pair that is not in the table: farther apart than max_distance, or coincident. */
#define BP_PPF_NO_KEY 0xffffffffu
/* Pairs with |d| <= BP_PPF_MIN_DIST_RATIO * max_distance are skipped: their angles are undefined. */
#define BP_PPF_MIN_DIST_RATIO 1e-6f
/* alpha is 0 when the rotated m_i lies within BP_PPF_AXIS_RATIO * |d| of the x axis (m_i on the
 * line of n_r): its angle about x is then undefined and would be rounding noise. */
#define BP_PPF_AXIS_RATIO 1e-4f
/* n_r is treated as exactly +-x when sin^2 of its angle to x is below this. */
#define BP_PPF_AXIS_SIN2 1e-12f

/* The bin of alpha in [-pi, pi): bins of angle_step starting at -pi. */
BP_FN bp_u32 bp_ppf_alpha_bin(float alpha, bp_ppf_quant q) {
  return bp_quantize(alpha + BP_PI_F, q.angle_step, q.n_alpha);
}

/* The bin of a scene pair's alpha_s for duplicate-vote suppression (ppf_vote.cl): bins of
 * 2 pi / n_alpha from -pi; inv_step = n_alpha / (2 pi), as the vote uses. */
BP_FN bp_u32 bp_alpha_s_bin(float alpha_s, float inv_step, bp_u32 n_alpha) {
  const float u = (alpha_s + BP_PI_F) * inv_step;
  bp_u32 b = u > 0.0f ? (bp_u32)u : 0u;
  return b < n_alpha ? b : n_alpha - 1u;
}

/* The key of a feature (|d|, angle(n1, d), angle(n2, d), angle(n1, n2)). */
BP_FN bp_u32 bp_ppf_feature_key(float dist, float a1, float a2, float a3, bp_ppf_quant q) {
  return bp_ppf_key(bp_quantize(dist, q.dist_step, q.n_dist),
                    bp_quantize(a1, q.angle_step, q.n_angle),
                    bp_quantize(a2, q.angle_step, q.n_angle),
                    bp_quantize(a3, q.angle_step, q.n_angle), q.n_angle);
}

/* A value of alpha in [-pi, pi), -0 made +0, so equal angles have equal bits (the table's order
 * within a bucket, and so the model file's bytes, must not depend on the sign of a zero). */
BP_FN float bp_ppf_wrap_alpha(float alpha) {
  if (alpha >= BP_PI_F) alpha = -BP_PI_F;
  return alpha + 0.0f;
}

#ifdef __OPENCL_VERSION__
/* Device side of the point pair feature, shared by training and detection so that model and
 * scene use one convention. The C++ reference (host/train/ppf_features.cpp) is written
 * independently with Eigen. Eight pairs at once, one reference point against eight points, as
 * float8 arithmetic: the kernels run one work item a work group (launch_tasks), where PoCL does
 * not vectorise across work items, so the SIMD lanes are used only if the code itself is vector
 * code (docs/decisions/2026-12-08-features-in-lanes.md). Branches are selects. */

/* atan2(y, x) in [-pi, pi] to about 2e-7 rad: PoCL's built-in atan2 costs ~150 ns on a CPU,
 * more than the rest of a point pair feature together. Cephes' atanf polynomial on
 * [0, tan(pi/8)], reduced from [0, 1] by pi/4 and from octants by symmetry. atan2(+-0, x < 0)
 * is +pi (alpha wraps pi to -pi anyway). */
BP_FN float8 bp_atan2_8(float8 y, float8 x) {
  const float8 ax = fabs(x), ay = fabs(y);
  const float8 hi = fmax(ax, ay), lo = fmin(ax, ay);
  float8 t = select((float8)(0.0f), lo / hi, hi > 0.0f); /* in [0, 1] */
  const int8 reduce = t > 0.41421356f;
  const float8 base = select((float8)(0.0f), (float8)(0.25f * BP_PI_F), reduce);
  t = select(t, (t - 1.0f) / (t + 1.0f), reduce);
  const float8 z = t * t;
  float8 a = base + ((((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
                      3.33329491539e-1f) * z * t + t);
  a = select(a, 0.5f * BP_PI_F - a, ay > ax);
  a = select(a, BP_PI_F - a, x < 0.0f);
  return select(a, -a, y < 0.0f);
}

/* Angle between a and b in [0, pi]: atan2 of |a x b| and a.b stays accurate near 0 and pi. */
BP_FN float8 bp_angle_between8(float8 ax, float8 ay, float8 az, float8 bx, float8 by, float8 bz) {
  const float8 cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  return bp_atan2_8(sqrt(cx * cx + cy * cy + cz * cz), ax * bx + ay * by + az * bz);
}

/* alpha_m of Drost 2010 for reference normal n (unit) and d = m_i - m_r (length len): rotate by
 * R, the rotation about n x e_x that takes n onto +x (Rodrigues; for n = -x a half turn about
 * z), and take the angle of R d about x, measured from +y towards +z: R d = R_x(alpha) (x, r, 0).
 * Detection: the model-to-scene rotation about x is alpha_s - alpha_m. */
BP_FN float8 bp_ppf_alpha8(float3 n, float8 dx, float8 dy, float8 dz, float8 len) {
  const float s = n.y * n.y + n.z * n.z; /* sin^2 of the angle between n and x */
  float8 y, z;
  if (s > BP_PPF_AXIS_SIN2) {
    const float c = n.x;
    /* 1 / (1 + c), written as (1 - c) / s when c < 0 where 1 + c cancels */
    const float k = c >= 0.0f ? 1.0f / (1.0f + c) : (1.0f - c) / s;
    const float8 ad = n.z * dy - n.y * dz; /* (n x e_x) . d */
    y = c * dy - n.y * dx + n.z * ad * k;
    z = c * dz - n.z * dx - n.y * ad * k;
  } else if (n.x > 0.0f) {
    y = dy;
    z = dz;
  } else {
    y = -dy;
    z = dz;
  }
  const float8 lim = BP_PPF_AXIS_RATIO * len;
  float8 alpha = bp_atan2_8(z, y);
  alpha = select(alpha, (float8)(-BP_PI_F), alpha >= BP_PI_F) + 0.0f; /* bp_ppf_wrap_alpha */
  return select(alpha, (float8)(0.0f), y * y + z * z <= lim * lim);
}

/* bp_quantize, eight at once. */
BP_FN uint8 bp_quantize8(float8 value, float step, uint bins) {
  const float8 q = floor(value / step);
  const float8 clamped = fmin(select((float8)(0.0f), q, q >= 0.0f), (float)(bins - 1u));
  return convert_uint8(clamped);
}

/* The keys of the pairs (p1 = m_r, n1) -> (p2 = m_i, n2) for eight points i, or BP_PPF_NO_KEY
 * where skipped; *alpha gets alpha_m (0 where skipped). Normals must be unit. */
BP_FN uint8 bp_ppf_pair8(float3 p1, float3 n1, float8 x2, float8 y2, float8 z2, float8 nx2,
                         float8 ny2, float8 nz2, bp_ppf_quant q, float8* alpha) {
  const float8 dx = x2 - p1.x, dy = y2 - p1.y, dz = z2 - p1.z;
  const float8 dist = sqrt(dx * dx + dy * dy + dz * dz);
  const int8 skip = ~(dist <= q.max_distance) | (dist <= BP_PPF_MIN_DIST_RATIO * q.max_distance);
  const float8 n1x = n1.x, n1y = n1.y, n1z = n1.z;
  const uint na = q.n_angle;
  const uint8 key =
      ((bp_quantize8(dist, q.dist_step, q.n_dist) * na +
        bp_quantize8(bp_angle_between8(n1x, n1y, n1z, dx, dy, dz), q.angle_step, na)) * na +
       bp_quantize8(bp_angle_between8(nx2, ny2, nz2, dx, dy, dz), q.angle_step, na)) * na +
      bp_quantize8(bp_angle_between8(n1x, n1y, n1z, nx2, ny2, nz2), q.angle_step, na);
  *alpha = select(bp_ppf_alpha8(n1, dx, dy, dz, dist), (float8)(0.0f), skip);
  return select(key, (uint8)(BP_PPF_NO_KEY), skip);
}

/* x, y and z of the float4s v[i0 .. i0 + 7] (0 past n). */
BP_FN void bp_load_xyz8(__global const float4* v, uint i0, uint n, float8* x, float8* y,
                        float8* z) {
  if (i0 + 8u <= n) {
    const __global float* f = (const __global float*)(v + i0);
    const float16 a = vload16(0, f), b = vload16(1, f);
    *x = (float8)(a.s048c, b.s048c);
    *y = (float8)(a.s159d, b.s159d);
    *z = (float8)(a.s26ae, b.s26ae);
    return;
  }
  float px[8], py[8], pz[8];
  for (uint l = 0; l < 8u; ++l) {
    const float4 p = i0 + l < n ? v[i0 + l] : (float4)(0.0f);
    px[l] = p.x, py[l] = p.y, pz[l] = p.z;
  }
  *x = vload8(0, px), *y = vload8(0, py), *z = vload8(0, pz);
}

/* The pairs of reference point (pr, nr) with points i0 .. i0 + 7 of the cloud: BP_PPF_NO_KEY for
 * a point past n, for point `self` (the reference itself) and for skipped pairs. */
BP_FN uint8 bp_ppf_pairs_at(float3 pr, float3 nr, __global const float4* points,
                            __global const float4* normals, uint i0, uint n, uint self,
                            bp_ppf_quant q, float8* alpha) {
  float8 x, y, z, nx, ny, nz;
  bp_load_xyz8(points, i0, n, &x, &y, &z);
  bp_load_xyz8(normals, i0, n, &nx, &ny, &nz);
  const uint8 i = i0 + (uint8)(0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u);
  const int8 out = as_int8(i >= n) | as_int8(i == self);
  float8 a;
  const uint8 key = bp_ppf_pair8(pr, nr, x, y, z, nx, ny, nz, q, &a);
  *alpha = select(a, (float8)(0.0f), out);
  return select(key, (uint8)(BP_PPF_NO_KEY), out);
}

/* Writes the eight values at out[0 .. 7], or those below `count` when fewer remain (alphas as
 * their bits: as_uint8, the buffer cast). */
BP_FN void bp_store8(uint8 v, __global uint* out, uint count) {
  if (count >= 8u) {
    vstore8(v, 0, out);
    return;
  }
  uint t[8];
  vstore8(v, 0, t);
  for (uint l = 0; l < count; ++l) out[l] = t[l];
}
#endif

#endif /* BINPICK_SHARED_H */
