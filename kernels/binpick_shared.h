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
 * independently with Eigen. */

/* atan2(y, x) in [-pi, pi] to about 2e-7 rad: PoCL's built-in atan2 costs ~150 ns on a CPU,
 * more than the rest of a point pair feature together. Cephes' atanf polynomial on
 * [0, tan(pi/8)], reduced from [0, 1] by pi/4 and from octants by symmetry. atan2(+-0, x < 0)
 * is +pi (alpha wraps pi to -pi anyway). */
BP_FN float bp_atan2(float y, float x) {
  const float ax = fabs(x), ay = fabs(y);
  const float hi = fmax(ax, ay), lo = fmin(ax, ay);
  float t = hi > 0.0f ? lo / hi : 0.0f; /* in [0, 1] */
  float base = 0.0f;
  if (t > 0.41421356f) {
    base = 0.25f * BP_PI_F;
    t = (t - 1.0f) / (t + 1.0f);
  }
  const float z = t * t;
  float a = base + ((((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
                     3.33329491539e-1f) * z * t + t);
  if (ay > ax) a = 0.5f * BP_PI_F - a;
  if (x < 0.0f) a = BP_PI_F - a;
  return y < 0.0f ? -a : a;
}

/* Angle between a and b in [0, pi]: atan2 of |a x b| and a.b stays accurate near 0 and pi. */
BP_FN float bp_angle_between(float3 a, float3 b) { return bp_atan2(length(cross(a, b)), dot(a, b)); }

/* alpha_m of Drost 2010 for reference normal n (unit) and d = m_i - m_r: rotate by R, the
 * rotation about n x e_x that takes n onto +x (Rodrigues; for n = -x a half turn about z), and
 * take the angle of R d about x, measured from +y towards +z: R d = R_x(alpha) (x, r, 0).
 * Detection: the model-to-scene rotation about x is alpha_s - alpha_m. */
BP_FN float bp_ppf_alpha(float3 n, float3 d) {
  const float s = n.y * n.y + n.z * n.z; /* sin^2 of the angle between n and x */
  float y, z;
  if (s > BP_PPF_AXIS_SIN2) {
    const float c = n.x;
    /* 1 / (1 + c), written as (1 - c) / s when c < 0 where 1 + c cancels */
    const float k = c >= 0.0f ? 1.0f / (1.0f + c) : (1.0f - c) / s;
    const float ad = n.z * d.y - n.y * d.z; /* (n x e_x) . d */
    y = c * d.y - n.y * d.x + n.z * ad * k;
    z = c * d.z - n.z * d.x - n.y * ad * k;
  } else if (n.x > 0.0f) {
    y = d.y;
    z = d.z;
  } else {
    y = -d.y;
    z = d.z;
  }
  const float lim = BP_PPF_AXIS_RATIO * length(d);
  if (y * y + z * z <= lim * lim) return 0.0f;
  return bp_ppf_wrap_alpha(bp_atan2(z, y));
}

/* The key of the pair (p1 = m_r, n1) -> (p2 = m_i, n2), or BP_PPF_NO_KEY if skipped; *alpha gets
 * alpha_m. Normals must be unit. */
BP_FN bp_u32 bp_ppf_pair(float3 p1, float3 n1, float3 p2, float3 n2, bp_ppf_quant q,
                         float* alpha) {
  const float3 d = p2 - p1;
  const float dist = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  *alpha = 0.0f;
  if (!(dist <= q.max_distance) || dist <= BP_PPF_MIN_DIST_RATIO * q.max_distance)
    return BP_PPF_NO_KEY;
  *alpha = bp_ppf_alpha(n1, d);
  return bp_ppf_feature_key(dist, bp_angle_between(n1, d), bp_angle_between(n2, d),
                            bp_angle_between(n1, n2), q);
}
#endif

#endif /* BINPICK_SHARED_H */
