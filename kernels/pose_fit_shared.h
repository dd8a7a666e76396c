/* Pose refinement and verification against a depth image (kernels/pose_fit.cl and its C++
 * reference, host/detect/refine/pose_fit.cpp), shared so that both classify every model point the
 * same way. Valid OpenCL C 1.2 and C++20; include after binpick_shared.h.
 *
 * A pose is compared with the measured point image through the model's points: each point is
 * posed, and if it faces the camera, projects into the image and is the nearest model surface in
 * its cell of a coarse z-buffer of the posed model (so the far side of a concave part, hidden
 * behind its near side, does not count), it is visible, and the measured point at its pixel
 * says what the sensor saw there:
 *   missing      no depth at that pixel: neutral (shadows, shiny metal, out of range);
 *   inlier       measured point within `tolerance` of the model surface along the ray
 *                (bp_fit_classify);
 *   see-through  otherwise, measured depth farther: the sensor looks through the part;
 *   occluded     otherwise, measured depth nearer: something lies in front of the part.
 * Visible points with a measured point within `gate` along the ray also give one point-to-plane
 * term of Gauss-Newton ICP (projective association), weighted by Tukey's biweight.
 *
 * The outline (with `outline` > 0): every empty z-buffer cell next to one the posed model fills
 * lies just outside the part's silhouette. A real part's outline is mostly a depth step down to
 * what it lies on; where the measured surface there continues at the model's depth (within
 * `outline`), the sensor sees surface where the pose says the part ends: a pose on the wrong
 * object, or shifted. Counted per cell: continue, step (farther), nothing (nearer: an occluder,
 * or no depth).
 *
 * Residuals (with `residuals` != 0): the point-to-plane residual of every point that gives an
 * ICP term, NaN for the others, and the class of every point (BP_FIT_HIDDEN also for points that
 * face away or fall outside the image or grid), one each per model point (the patch bias,
 * host/detect/verify/patch_bias.hpp, looks for model regions whose residuals do not average out; the
 * look-alike holes, host/detect/verify/lookalike_holes.hpp, need to tell no depth from something in front). */
#ifndef BINPICK_POSE_FIT_SHARED_H
#define BINPICK_POSE_FIT_SHARED_H

#ifdef __OPENCL_VERSION__
#define BP_FIT_SQRT sqrt
#else
#define BP_FIT_SQRT std::sqrt
#endif

/* Work items per pose: one work group fits one pose. */
#define BP_FIT_GROUP 64
/* Largest z-buffer grid side (cells). */
#define BP_FIT_MAX_DIM 64
/* A model point faces the camera when the cosine between its normal and the ray to the camera
 * is at least this (about 80 degrees): grazing surfaces are where depth sensors see least. */
#define BP_FIT_MIN_COS 0.17f

#define BP_FIT_HIDDEN 0u /* faces away, outside the image or grid, or behind the model itself */
#define BP_FIT_MISSING 1u
#define BP_FIT_INLIER 2u
#define BP_FIT_SEE_THROUGH 3u
#define BP_FIT_OCCLUDED 4u
#define BP_FIT_CLASSES 5u

/* One pose to fit; all 4-byte scalars (100 bytes). */
typedef struct {
  float r[9];       /* model -> camera rotation, row-major */
  float t[3];       /* mm */
  float centre[3];  /* camera frame: the posed model centroid, the pivot of the ICP update */
  float gate;       /* mm: a measured point farther than this along the ray is not associated */
  float tolerance;  /* mm: |measured - model depth| within this is an inlier */
  float slack;      /* mm: a point within this of its z-buffer cell's nearest is not hidden */
  float u0, v0;     /* pixel coordinates of the z-buffer grid's corner */
  float cell;       /* z-buffer cell side, pixels */
  bp_u32 dim;       /* cells per side, <= BP_FIT_MAX_DIM; 0: nothing can be visible */
  float outline;    /* mm: the outline's depth tolerance; 0: no outline */
  bp_u32 residuals; /* != 0: write each model point's residual (NaN where it gives no term) and
                     * class */
  float near_gate;  /* mm, > 0: a measured point nearer the camera than the model's surface by
                     * more than this (along the normal) gives no ICP term: something lying on
                     * the part (bp_near_gate); 0: the gate alone */
} bp_pose_fit;

/* What one work item (kernel) or one pose (reference) adds up. */
typedef struct {
  float jtj[21];    /* upper triangle of sum w a a^T, row by row; a = ((q - c) x n, n) */
  float jtr[6];     /* sum w a r */
  float cost;       /* sum w r^2 */
  bp_u32 count[BP_FIT_CLASSES]; /* model points per class */
  bp_u32 used;      /* terms with weight > 0 */
  float agreement;  /* sum over inliers of 1 - (r / tolerance)^2: how well, not only whether */
  bp_u32 outline_continue; /* outline cells where the measured surface continues */
  bp_u32 outline_step;     /* outline cells where it steps down */
} bp_fit_sums;

#define BP_FIT_OUTLINE_NONE 0u
#define BP_FIT_OUTLINE_CONTINUE 1u
#define BP_FIT_OUTLINE_STEP 2u

/* Posed model point q = R m + t and normal nq = R n; its pixel (row-major index) and z-buffer
 * cell. Returns 0 if it falls outside the image or the grid, else 2 if it faces the camera and
 * 1 if not (the z-buffer takes both: a wall seen edge on still hides what lies behind it). */
BP_FN int bp_fit_project(const bp_pose_fit* f, const bp_camera* cam, float mx, float my, float mz,
                         float nx, float ny, float nz, float* q, float* nq, bp_u32* pixel,
                         bp_u32* cell) {
  for (int i = 0; i < 3; ++i) {
    q[i] = f->r[3 * i] * mx + f->r[3 * i + 1] * my + f->r[3 * i + 2] * mz + f->t[i];
    nq[i] = f->r[3 * i] * nx + f->r[3 * i + 1] * ny + f->r[3 * i + 2] * nz;
  }
  if (!(q[2] > 0.0f)) return 0;
  const float u = cam->fx * q[0] / q[2] + cam->cx;
  const float v = cam->fy * q[1] / q[2] + cam->cy;
  const float pu = BP_FLOOR(u + 0.5f), pv = BP_FLOOR(v + 0.5f);
  if (!(pu >= 0.0f && pv >= 0.0f && pu < (float)cam->width && pv < (float)cam->height)) return 0;
  const float gu = BP_FLOOR((u - f->u0) / f->cell), gv = BP_FLOOR((v - f->v0) / f->cell);
  if (!(gu >= 0.0f && gv >= 0.0f && gu < (float)f->dim && gv < (float)f->dim)) return 0;
  *pixel = (bp_u32)pv * cam->width + (bp_u32)pu;
  *cell = (bp_u32)gv * f->dim + (bp_u32)gu;
  /* Facing: -nq . q >= cos * |q| * |nq|. */
  const float dot = -(nq[0] * q[0] + nq[1] * q[1] + nq[2] * q[2]);
  const float len2 = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) *
                     (nq[0] * nq[0] + nq[1] * nq[1] + nq[2] * nq[2]);
  return dot > 0.0f && dot * dot >= BP_FIT_MIN_COS * BP_FIT_MIN_COS * len2 ? 2 : 1;
}

/* The class of a visible model point q (normal nq) at depth q[2] whose cell's nearest model
 * depth is zmin, given the measured point p there (w = 0: no data). An inlier's measured point
 * lies within the tolerance of the model's tangent plane *along the ray*, and not farther than
 * three tolerances in depth. Along the ray, because a depth sensor's noise lies along its rays:
 * the point-to-plane distance r shrinks it by the cosine c between the normal and the ray, so
 * on faces seen obliquely nearly every noisy point agreed, and at 5 % noise a plate seen edge
 * on, or a shaft's flanks, outscored a part seen face on. But a pixel also spans a width of the
 * surface (the measured point may come from anywhere in it, the model point is at one place),
 * which moves r by up to half the pixel's width times the sine. So |r| may reach
 * tolerance x c + pixel / 2 x sine: the same share of a right pose's points agrees whichever
 * way its faces turn (docs/detect/verify.md, "Agreement";
 * docs/decisions/2026-11-28-inliers-along-the-ray.md). */
BP_FN bp_u32 bp_fit_classify(const bp_pose_fit* f, const bp_camera* cam, const float* q,
                             const float* nq, float zmin, float px, float py, float pz, float pw,
                             float* agreement) {
  *agreement = 0.0f;
  if (q[2] > zmin + f->slack) return BP_FIT_HIDDEN;
  if (pw == 0.0f) return BP_FIT_MISSING;
  const float dz = pz - q[2];
  const float r = nq[0] * (px - q[0]) + nq[1] * (py - q[1]) + nq[2] * (pz - q[2]);
  const float qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
  const float nn = nq[0] * nq[0] + nq[1] * nq[1] + nq[2] * nq[2];
  float c = -(nq[0] * q[0] + nq[1] * q[1] + nq[2] * q[2]) / BP_FIT_SQRT(qq * nn);
  c = c < 1.0f ? c : 1.0f;
  const float allowed = f->tolerance * c + 0.5f * (q[2] / cam->fx) * BP_FIT_SQRT(1.0f - c * c);
  if (r <= allowed && -r <= allowed && dz <= 3.0f * f->tolerance && -dz <= 3.0f * f->tolerance) {
    const float u = r / allowed;
    *agreement = 1.0f - u * u;
    return BP_FIT_INLIER;
  }
  return dz > 0.0f ? BP_FIT_SEE_THROUGH : BP_FIT_OCCLUDED;
}

/* The near gate for an association gate and tolerance (mm) and the image's depth noise sigma
 * (mm): once the gate is under 3 tolerances (the pose is near), a measured point more than
 * max(tolerance / 2, 3 sigma) nearer than the surface is taken for something lying on the part
 * (a plate on the plate, a part leaning on it), not for the part: inside the gate it would pull
 * the pose toward itself. 0 (off) while the gate is wider. */
BP_FN float bp_near_gate(float gate, float tolerance, float noise) {
  if (!(gate < 3.0f * tolerance)) return 0.0f;
  const float cut = 0.5f * tolerance > 3.0f * noise ? 0.5f * tolerance : 3.0f * noise;
  return cut < gate ? cut : 0.0f;
}

/* The ICP term of a visible point q (normal nq) and the measured point p: the point-to-plane
 * residual r = nq . (p - q) and a = ((q - c) x nq, nq), so that a small rotation w about c and
 * translation v change r by -a . (w, v). Returns the weight, 0 if p is beyond the gate. */
BP_FN float bp_fit_term(const bp_pose_fit* f, const float* q, const float* nq, float px, float py,
                        float pz, float* a, float* r) {
  if (!(pz - q[2] <= f->gate && q[2] - pz <= f->gate)) return 0.0f;
  const float res = nq[0] * (px - q[0]) + nq[1] * (py - q[1]) + nq[2] * (pz - q[2]);
  const float u = res / f->gate;
  if (!(u * u < 1.0f)) return 0.0f;
  if (f->near_gate > 0.0f && res > f->near_gate) return 0.0f; /* r > 0: nearer the camera */
  const float cx = q[0] - f->centre[0], cy = q[1] - f->centre[1], cz = q[2] - f->centre[2];
  a[0] = cy * nq[2] - cz * nq[1];
  a[1] = cz * nq[0] - cx * nq[2];
  a[2] = cx * nq[1] - cy * nq[0];
  a[3] = nq[0];
  a[4] = nq[1];
  a[5] = nq[2];
  *r = res;
  const float b = 1.0f - u * u;
  return b * b;
}

/* The pixel at the centre of z-buffer cell (gu, gv); 0 if it falls outside the image. */
BP_FN int bp_fit_outline_pixel(const bp_pose_fit* f, const bp_camera* cam, bp_u32 gu, bp_u32 gv,
                               bp_u32* pixel) {
  const float u = f->u0 + ((float)gu + 0.5f) * f->cell;
  const float v = f->v0 + ((float)gv + 0.5f) * f->cell;
  const float pu = BP_FLOOR(u + 0.5f), pv = BP_FLOOR(v + 0.5f);
  if (!(pu >= 0.0f && pv >= 0.0f && pu < (float)cam->width && pv < (float)cam->height)) return 0;
  *pixel = (bp_u32)pv * cam->width + (bp_u32)pu;
  return 1;
}

/* An outline cell whose filled neighbours' nearest model depth is zn, against the measured depth
 * pz there (pw = 0: no data). */
BP_FN bp_u32 bp_fit_outline_class(const bp_pose_fit* f, float zn, float pz, float pw) {
  if (pw == 0.0f) return BP_FIT_OUTLINE_NONE;
  const float dz = pz - zn;
  if (dz > f->outline) return BP_FIT_OUTLINE_STEP;
  if (dz < -f->outline) return BP_FIT_OUTLINE_NONE;
  return BP_FIT_OUTLINE_CONTINUE;
}

#endif /* BINPICK_POSE_FIT_SHARED_H */
