#include "host/detect/hypotheses/hypotheses.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "host/core/error.hpp"
#include "host/detect/scene/scene_chunks.hpp"
#include "host/detect/scene/scene_crop.hpp"
#include "host/detect/scene/scene_normals.hpp"
#include "kernels/scene_shared.h"

namespace binpick {
namespace {

void check_filtered(const PointImage& points, const std::vector<float>& filtered) {
  check_point_image(points);
  if (filtered.size() != std::size_t(points.width) * points.height)
    throw InputError("filtered depth has " + std::to_string(filtered.size()) +
                     " values for a point image of " + std::to_string(points.width) + " x " +
                     std::to_string(points.height));
}

Hypothesis from_shared(const bp_hypothesis& h) {
  return {h.pixel, h.u, h.v, h.depth, Eigen::Vector3f(h.x, h.y, h.z)};
}

// Highest first, up to the first round that found none.
std::vector<Hypothesis> from_device(const std::vector<bp_hypothesis>& hyps) {
  std::vector<Hypothesis> out;
  for (const bp_hypothesis& h : hyps) {
    if (h.pixel == BP_NO_PIXEL) break;  // once none is left, no later round finds one
    out.push_back(from_shared(h));
  }
  return out;
}

// The rounds with a camera (find_hypotheses): tiles instead of chunks, and after the
// first round only the exclusion sphere's rectangle excluded and its tiles scanned again. Every
// other tile's argmin is unchanged (nothing in it was excluded), so each round picks the pixel
// the whole-image rounds pick.
std::vector<Hypothesis> rounds_on_tiles(ocl::Device& dev, const ocl::Buffer<float>& points,
                                        const ocl::Buffer<float>& filtered,
                                        const ocl::Buffer<float>& keys, std::uint32_t width,
                                        std::uint32_t height, const HypothesisOptions& opt,
                                        const bp_camera& cam, ocl::Buffer<std::uint8_t>& excluded) {
  if (cam.width != width || cam.height != height)
    throw InputError("the hypotheses' camera is " + std::to_string(cam.width) + " x " +
                     std::to_string(cam.height) + " pixels, the image " + std::to_string(width) +
                     " x " + std::to_string(height));
  const Tiles t = tiles_for(width, height);
  ocl::Buffer<float> part_depth(dev, t.count());
  ocl::Buffer<cl_uint> part_pixel(dev, t.count());
  ocl::Buffer<bp_hypothesis> hyps(dev, opt.count);
  cl::Kernel argmin = dev.kernel("hypotheses.cl", "hyp_tile_argmin");
  cl::Kernel select = dev.kernel("hypotheses.cl", "hyp_select");
  cl::Kernel exclude = dev.kernel("hypotheses.cl", "hyp_exclude_rect");
  const float radius2 = opt.exclusion_radius * opt.exclusion_radius;
  // The tiles to scan: all of them in the first round.
  std::uint32_t tx0 = 0, ty0 = 0, ntx = t.x, nty = t.y;
  std::vector<Hypothesis> out;
  for (cl_uint k = 0; k < opt.count; ++k) {
    ocl::launch(dev, argmin, std::size_t(ntx) * nty, keys, excluded, cl_uint(width),
                cl_uint(height), cl_uint(t.w), cl_uint(t.h), cl_uint(t.x), cl_uint(tx0),
                cl_uint(ty0), cl_uint(ntx), cl_uint(nty), part_depth, part_pixel);
    ocl::launch(dev, select, 1, part_depth, part_pixel, cl_uint(t.count()), points, filtered,
                cl_uint(width), k, hyps);
    const bp_hypothesis h = hyps.read(dev, k + 1)[k];
    if (h.pixel == BP_NO_PIXEL) break;  // no later round finds one
    out.push_back(from_shared(h));
    if (k + 1 == opt.count) break;  // the last round's exclusion would only serve a next round
    CropOptions sphere;
    sphere.centre = Eigen::Vector3f(h.x, h.y, h.z);
    sphere.radius = opt.exclusion_radius;
    std::array<std::uint32_t, 4> r = crop_pixel_rect(cam, sphere);
    // The own pixel is excluded whatever the radius (it lies in the rectangle; made sure).
    r = {std::min(r[0], h.u), std::min(r[1], h.v), std::max(r[2], h.u + 1), std::max(r[3], h.v + 1)};
    ocl::launch(dev, exclude, std::size_t(r[2] - r[0]) * (r[3] - r[1]), points, cl_uint(width),
                cl_uint(r[0]), cl_uint(r[1]), cl_uint(r[2] - r[0]), cl_uint(r[3] - r[1]), hyps, k,
                radius2, excluded);
    tx0 = r[0] / t.w, ty0 = r[1] / t.h;
    ntx = (r[2] - 1) / t.w + 1 - tx0, nty = (r[3] - 1) / t.h + 1 - ty0;
  }
  return out;
}

}  // namespace

Tiles tiles_for(std::uint32_t width, std::uint32_t height) {
  Tiles t;
  t.x = (width + t.w - 1) / t.w;
  t.y = (height + t.h - 1) / t.h;
  return t;
}

void check(const HypothesisOptions& opt) {
  if (!(opt.exclusion_radius >= 0) || std::isinf(opt.exclusion_radius))
    throw InputError("hypothesis exclusion radius must be finite and non-negative (mm)");
  if (opt.count > 10000) throw InputError("at most 10000 hypotheses");
  if (opt.up && !(std::abs(opt.up->norm() - 1.0f) < 1e-3f))
    throw InputError("the hypotheses' up direction must be a unit vector");
}

std::vector<float> height_keys_reference(const PointImage& points,
                                         const std::vector<float>& filtered,
                                         const Eigen::Vector3f& up) {
  check_filtered(points, filtered);
  std::vector<float> key(filtered.size(), 0.0f);
  for (std::size_t i = 0; i < filtered.size(); ++i) {
    const float d = filtered[i];
    if (!(d > 0.0f)) continue;
    const float* p = &points.xyzw[4 * i];
    const float s = d / p[2];
    const float x = p[0] * s, y = p[1] * s;
    const float k = -((up.x() * x + up.y() * y) + up.z() * d);
    key[i] = k > 0.0f ? k : std::numeric_limits<float>::min();
  }
  return key;
}

std::vector<Hypothesis> find_hypotheses(ocl::Device& dev, const ocl::Buffer<float>& points,
                                        const ocl::Buffer<float>& filtered, std::uint32_t width,
                                        std::uint32_t height, const HypothesisOptions& opt,
                                        const ocl::Buffer<std::uint8_t>* mask,
                                        const bp_camera* camera) {
  check(opt);
  const std::size_t n = std::size_t(width) * height;
  const Chunks ch = chunks_for(n);
  if (opt.count == 0 || ch.count == 0) return {};
  if (mask && mask->size() != n)
    throw InputError("the hypothesis mask has " + std::to_string(mask->size()) +
                     " bytes for an image of " + std::to_string(n) + " pixels");
  if (points.size() < 4 * n || filtered.size() < n)
    throw InputError("the hypotheses' point or filtered-depth buffer is smaller than the image");
  ocl::Buffer<std::uint8_t> excluded(dev, n);
  if (mask) {
    cl::Kernel init = dev.kernel("hypotheses.cl", "hyp_exclude_masked");
    ocl::launch(dev, init, n, *mask, cl_uint(n), excluded);
  } else {
    excluded.fill(dev, 0);
  }
  // The argmin reads keys: the filtered depth, or the height keys along opt.up.
  std::optional<ocl::Buffer<float>> height_keys;
  if (opt.up) {
    height_keys.emplace(dev, n);
    cl::Kernel key = dev.kernel("hypotheses.cl", "hyp_height_key");
    ocl::launch(dev, key, n, points, filtered, cl_uint(n), opt.up->x(), opt.up->y(), opt.up->z(),
                *height_keys);
  }
  const ocl::Buffer<float>& keys = height_keys ? *height_keys : filtered;
  if (camera)
    return rounds_on_tiles(dev, points, filtered, keys, width, height, opt, *camera, excluded);
  ocl::Buffer<float> part_depth(dev, ch.count);
  ocl::Buffer<cl_uint> part_pixel(dev, ch.count);
  ocl::Buffer<bp_hypothesis> hyps(dev, opt.count);
  cl::Kernel argmin = dev.kernel("hypotheses.cl", "hyp_chunk_argmin");
  cl::Kernel select = dev.kernel("hypotheses.cl", "hyp_select");
  cl::Kernel exclude = dev.kernel("hypotheses.cl", "hyp_exclude");
  const float radius2 = opt.exclusion_radius * opt.exclusion_radius;
  for (cl_uint k = 0; k < opt.count; ++k) {
    ocl::launch(dev, argmin, ch.count, keys, excluded, cl_uint(n), cl_uint(ch.size),
                part_depth, part_pixel);
    ocl::launch(dev, select, 1, part_depth, part_pixel, cl_uint(ch.count), points, filtered,
                cl_uint(width), k, hyps);
    // The last round's exclusion would only serve a next round.
    if (k + 1 < opt.count) ocl::launch(dev, exclude, n, points, cl_uint(n), hyps, k, radius2, excluded);
  }
  return from_device(hyps.read(dev));
}

std::vector<Hypothesis> find_hypotheses(ocl::Device& dev, const PointImage& points,
                                        const std::vector<float>& filtered,
                                        const HypothesisOptions& opt,
                                        const std::vector<std::uint8_t>* mask,
                                        const bp_camera* camera) {
  check_filtered(points, filtered);
  check(opt);
  ocl::Buffer<float> p(dev, std::span<const float>(points.xyzw), CL_MEM_READ_ONLY);
  ocl::Buffer<float> f(dev, std::span<const float>(filtered), CL_MEM_READ_ONLY);
  if (!mask) return find_hypotheses(dev, p, f, points.width, points.height, opt, nullptr, camera);
  const ocl::Buffer<std::uint8_t> m(dev, std::span<const std::uint8_t>(*mask), CL_MEM_READ_ONLY);
  return find_hypotheses(dev, p, f, points.width, points.height, opt, &m, camera);
}

std::vector<Hypothesis> find_hypotheses_reference(const PointImage& points,
                                                  const std::vector<float>& filtered,
                                                  const HypothesisOptions& opt,
                                                  const std::vector<std::uint8_t>* mask) {
  check_filtered(points, filtered);
  check(opt);
  const std::size_t n = filtered.size();
  if (mask && mask->size() != n) throw InputError("the hypothesis mask does not match the image");
  const float radius2 = opt.exclusion_radius * opt.exclusion_radius;
  const std::vector<float> keys =
      opt.up ? height_keys_reference(points, filtered, *opt.up) : filtered;
  std::vector<std::uint8_t> excluded(n, 0);
  if (mask)
    for (std::size_t i = 0; i < n; ++i) excluded[i] = (*mask)[i] ? 0 : 1;
  std::vector<Hypothesis> out;
  for (std::uint32_t k = 0; k < opt.count; ++k) {
    float best = std::numeric_limits<float>::infinity();
    std::size_t best_i = n;
    for (std::size_t i = 0; i < n; ++i)
      if (keys[i] > 0.0f && !excluded[i] && keys[i] < best) best = keys[i], best_i = i;
    if (best_i == n) break;
    const float* p = &points.xyzw[4 * best_i];
    const float s = filtered[best_i] / p[2];
    bp_hypothesis h{std::uint32_t(best_i), std::uint32_t(best_i % points.width),
                    std::uint32_t(best_i / points.width), filtered[best_i], p[0] * s, p[1] * s,
                    filtered[best_i], {0, 0}};
    out.push_back(from_shared(h));
    for (std::size_t i = 0; i < n; ++i) {
      const float* q = &points.xyzw[4 * i];
      if (i == best_i || (q[3] != 0.0f && bp_dist2(q[0], q[1], q[2], h.x, h.y, h.z) <= radius2))
        excluded[i] = 1;
    }
  }
  return out;
}

std::vector<Hypothesis> find_hypotheses(const PreparedScene& scene, const HypothesisOptions& opt,
                                        StageTimings* timings) {
  Stopwatch clock;
  std::vector<Hypothesis> out =
      scene.device ? find_hypotheses(*scene.device->dev, scene.device->points,
                                     scene.device->filtered, scene.width, scene.height, opt)
                   : find_hypotheses_reference(scene.points, scene.filtered_depth, opt);
  if (timings) timings->push_back({"hypotheses", clock.lap()});
  return out;
}

}  // namespace binpick
