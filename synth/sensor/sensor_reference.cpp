#include "synth/sensor/sensor_reference.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <limits>
#include <string>

#include "host/core/error.hpp"
#include "synth/render/bin_noise.hpp"
#include "synth/sensor/sensor_patches.hpp"

namespace binpick {
namespace {

bool has_surface(float z) { return z > 0.0f && z <= FLT_MAX; }  // false for NaN and infinity

bool measurable(const SensorParams& p, float z) { return has_surface(z) && sensor_in_range(p, z); }

std::size_t index(const SensorParams& p, std::uint32_t u, std::uint32_t v) {
  return std::size_t(v) * p.width + u;
}

// A pixel's surface point: its ray (z component 1), the point and its normal as given, or
// facing the camera (-point) when that has no length or is not finite.
struct Surfel {
  std::uint32_t u, v;
  float z, rx, ry, px, py, pz;
  std::array<float, 3> n;
};

Surfel surfel(const SensorImages& in, const SensorParams& p, std::uint32_t u, std::uint32_t v) {
  Surfel s;
  const std::size_t i = index(p, u, v);
  s.u = u, s.v = v, s.z = in.depth_mm[i];
  s.rx = (float(u) - p.cx) / p.fx, s.ry = (float(v) - p.cy) / p.fy;
  s.px = s.rx * s.z, s.py = s.ry * s.z, s.pz = s.z;
  s.n = {in.normals[3 * i], in.normals[3 * i + 1], in.normals[3 * i + 2]};
  const float len2 = (s.n[0] * s.n[0] + s.n[1] * s.n[1]) + s.n[2] * s.n[2];
  if (!(len2 > 1e-24f && len2 <= FLT_MAX)) s.n = {-s.px, -s.py, -s.pz};
  return s;
}

// Whether depth zj at pixel (uu, vv) lies on s's tangent plane, within edge_jump_mm: a steep
// surface is not a discontinuity, a step is.
bool same_surface(const SensorParams& p, const Surfel& s, std::uint32_t uu, std::uint32_t vv, float zj) {
  const float dx = (float(uu) - p.cx) / p.fx, dy = (float(vv) - p.cy) / p.fy;
  const float num = (s.n[0] * s.px + s.n[1] * s.py) + s.n[2] * s.pz;
  const float den = (s.n[0] * dx + s.n[1] * dy) + s.n[2];
  if (den == 0.0f) return false;  // the neighbour's ray runs along the plane
  const float d = std::fabs(zj - num / den);
  return d <= p.edge_jump_mm;  // false for NaN
}

// The largest depth change to a neighbour (3 x 3) on the same surface.
float local_slope(const SensorImages& in, const SensorParams& p, const Surfel& s) {
  float slope = 0.0f;
  for (int dv = -1; dv <= 1; ++dv)
    for (int du = -1; du <= 1; ++du) {
      const int uu = int(s.u) + du, vv = int(s.v) + dv;
      if (uu < 0 || vv < 0 || uu >= int(p.width) || vv >= int(p.height)) continue;
      const float zj = in.depth_mm[index(p, std::uint32_t(uu), std::uint32_t(vv))];
      if (!measurable(p, zj) || !same_surface(p, s, std::uint32_t(uu), std::uint32_t(vv), zj)) continue;
      slope = std::max(slope, std::fabs(zj - s.z));
    }
  return slope;
}

bool shadowed(const SensorImages& in, const std::vector<float>& raster, const SensorParams& p, const Surfel& s) {
  const float tolerance = p.shadow_tolerance_mm + p.slope_factor * local_slope(in, p, s);
  const float x = std::floor(projector_u(p, s.u, s.z)), y = std::floor(projector_v(p, s.v));
  if (!(x >= 0.0f && y >= 0.0f && x < float(p.proj_width) && y < float(p.proj_height))) return true;
  const float nearest = raster[std::size_t(y) * p.proj_width + std::size_t(x)];
  return s.z - nearest > tolerance;
}

std::array<float, 3> unit_normal(const Surfel& s) {
  const float len = std::sqrt((s.n[0] * s.n[0] + s.n[1] * s.n[1]) + s.n[2] * s.n[2]);
  return {s.n[0] / len, s.n[1] / len, s.n[2] / len};
}

bool grazing(const SensorParams& p, const Surfel& s) {
  const std::array<float, 3> n = unit_normal(s);
  const float plen = std::sqrt((s.px * s.px + s.py * s.py) + s.pz * s.pz);
  const float cos_camera = -((n[0] * s.px + n[1] * s.py) + n[2] * s.pz) / plen;
  const float tx = p.baseline_mm - s.px, ty = -s.py, tz = -s.pz;
  const float tlen = std::sqrt((tx * tx + ty * ty) + tz * tz);
  const float cos_projector = ((n[0] * tx + n[1] * ty) + n[2] * tz) / tlen;
  return cos_camera < p.cos_grazing || cos_projector < p.cos_grazing;
}

// Whether the normal lies within the specular cone around the bisector of the unit rays to
// the camera and to the projector.
bool specular(const SensorParams& p, const Surfel& s) {
  const std::array<float, 3> n = unit_normal(s);
  const float plen = std::sqrt((s.px * s.px + s.py * s.py) + s.pz * s.pz);
  const float tx = p.baseline_mm - s.px, ty = -s.py, tz = -s.pz;
  const float tlen = std::sqrt((tx * tx + ty * ty) + tz * tz);
  const float hx = -s.px / plen + tx / tlen, hy = -s.py / plen + ty / tlen, hz = -s.pz / plen + tz / tlen;
  const float hlen = std::sqrt((hx * hx + hy * hy) + hz * hz);
  const float cos_half = ((n[0] * hx + n[1] * hy) + n[2] * hz) / hlen;
  return cos_half > p.cos_specular;
}

bool near_edge(const SensorImages& in, const SensorParams& p, const Surfel& s) {
  const int r = p.edge_radius;
  for (int dv = -r; dv <= r; ++dv)
    for (int du = -r; du <= r; ++du) {
      const int uu = int(s.u) + du, vv = int(s.v) + dv;
      if (uu < 0 || vv < 0 || uu >= int(p.width) || vv >= int(p.height)) continue;
      const float zj = in.depth_mm[index(p, std::uint32_t(uu), std::uint32_t(vv))];
      if (!has_surface(zj) || !same_surface(p, s, std::uint32_t(uu), std::uint32_t(vv), zj)) return true;
    }
  return false;
}

// Whether the pixel lies in a patch without depth: the field at its (ideal) point.
bool in_patch(const SensorParams& p, const Surfel& s) {
  const float field = patch_field(patch_key(p.seed_lo, p.seed_hi), p.patch_inv_mm, s.px, s.py, s.pz);
  return field < p.patch_threshold;
}

// Noise along the ray, then quantisation.
float measured_depth(const SensorParams& p, std::uint32_t pixel, float z) {
  const std::uint64_t seed = (std::uint64_t(p.seed_hi) << 32) | p.seed_lo;
  const float axial = p.noise_a_mm + p.noise_b_per_mm * (z * z);
  const float sigma = std::sqrt(axial * axial + p.added_sigma_mm * p.added_sigma_mm);
  float out = z;
  if (sigma > 0.0f) out = std::max(z + sigma * pixel_gaussian(seed, pixel), 1e-3f * z);
  if (p.quant_mm > 0.0f) {
    if (p.quant_ref_mm > 0.0f) {  // a lattice in disparity: steps grow with z^2
      const float c = (p.quant_ref_mm * p.quant_ref_mm) / p.quant_mm;
      const float k = std::max(std::floor(c / out + 0.5f), 1.0f);
      out = c / k;
    } else {
      const float k = std::max(std::floor(out / p.quant_mm + 0.5f), 1.0f);
      out = k * p.quant_mm;
    }
  }
  return out;
}

}  // namespace

void check_sensor_images(const SensorImages& in, const SensorParams& p) {
  const std::size_t n = std::size_t(p.width) * p.height;
  if (in.width != p.width || in.height != p.height || in.depth_mm.size() != n ||
      in.normals.size() != 3 * n || in.gray.size() != n)
    throw InputError("sensor model input does not match the camera's " + std::to_string(p.width) +
                     " x " + std::to_string(p.height) + " pixels");
}

std::vector<float> projector_raster_reference(const SensorImages& in, const SensorParams& p) {
  check_sensor_images(in, p);
  std::vector<float> raster(std::size_t(p.proj_width) * p.proj_height, std::numeric_limits<float>::infinity());
  if (!(p.flags & kSensorShadows)) return raster;
  for (std::uint32_t v = 0; v < p.height; ++v)
    for (std::uint32_t u = 0; u < p.width; ++u) {
      const float z = in.depth_mm[index(p, u, v)];
      if (!measurable(p, z)) continue;
      const Surfel s = surfel(in, p, u, v);
      // The quad to the right and lower neighbours that lie on the same surface.
      const float pu = projector_u(p, u, z), pv = projector_v(p, v);
      float lo_u = pu, hi_u = pu, lo_v = pv, hi_v = pv, nearest = z;
      for (auto [du, dv] : {std::pair{1u, 0u}, {0u, 1u}, {1u, 1u}}) {
        const std::uint32_t uu = u + du, vv = v + dv;
        if (uu >= p.width || vv >= p.height) continue;
        const float zj = in.depth_mm[index(p, uu, vv)];
        if (!measurable(p, zj) || !same_surface(p, s, uu, vv, zj)) continue;
        const float qu = projector_u(p, uu, zj), qv = projector_v(p, vv);
        lo_u = std::min(lo_u, qu), hi_u = std::max(hi_u, qu);
        lo_v = std::min(lo_v, qv), hi_v = std::max(hi_v, qv);
        nearest = std::min(nearest, zj);
      }
      int x0 = int(std::floor(lo_u)), x1 = int(std::floor(hi_u));
      int y0 = int(std::floor(lo_v)), y1 = int(std::floor(hi_v));
      if (x1 - x0 >= kMaxFootprint || y1 - y0 >= kMaxFootprint) {  // stretched: the point only
        x0 = x1 = int(std::floor(pu)), y0 = y1 = int(std::floor(pv));
        nearest = z;
      }
      x0 = std::max(x0, 0), y0 = std::max(y0, 0);
      x1 = std::min(x1, int(p.proj_width) - 1), y1 = std::min(y1, int(p.proj_height) - 1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          float& cell = raster[std::size_t(y) * p.proj_width + std::size_t(x)];
          cell = std::min(cell, nearest);
        }
    }
  return raster;
}

SensorOutput sensor_measure_reference(const SensorImages& in, const std::vector<float>& raster,
                                      const SensorParams& p) {
  check_sensor_images(in, p);
  const std::size_t n = std::size_t(p.width) * p.height;
  SensorOutput out{std::vector<float>(n, 0.0f), std::vector<float>(3 * n, 0.0f),
                   std::vector<float>(3 * n, 0.0f), in.gray,
                   std::vector<std::uint8_t>(n, std::uint8_t(Dropout::valid))};
  for (std::uint32_t v = 0; v < p.height; ++v)
    for (std::uint32_t u = 0; u < p.width; ++u) {
      const std::size_t i = index(p, u, v);
      const float z = in.depth_mm[i];
      Dropout why = Dropout::valid;
      const Surfel s = surfel(in, p, u, v);
      if (!has_surface(z)) why = Dropout::no_surface;
      else if (!(p.flags & kSensorEffects)) why = Dropout::valid;
      else if (!sensor_in_range(p, z)) why = Dropout::out_of_range;
      else if ((p.flags & kSensorShadows) && shadowed(in, raster, p, s)) why = Dropout::shadow;
      else if (grazing(p, s)) why = Dropout::grazing;
      else if (specular(p, s)) why = Dropout::specular;
      else if (near_edge(in, p, s)) why = Dropout::edge;
      else if ((p.flags & kSensorPatches) && in_patch(p, s)) why = Dropout::patch;
      out.dropout[i] = std::uint8_t(why);
      if (why == Dropout::shadow) out.gray[i] = std::uint8_t(kShadowGray);
      if (why != Dropout::valid) continue;
      const float depth = (p.flags & kSensorEffects) ? measured_depth(p, std::uint32_t(i), z) : z;
      out.depth_mm[i] = depth;
      out.points[3 * i] = s.rx * depth;
      out.points[3 * i + 1] = s.ry * depth;
      out.points[3 * i + 2] = depth;
      // Ideal: the normal as given (the images stay as rendered); otherwise the unit normal.
      const std::array<float, 3> normal =
          (p.flags & kSensorEffects)
              ? unit_normal(s)
              : std::array<float, 3>{in.normals[3 * i], in.normals[3 * i + 1], in.normals[3 * i + 2]};
      for (int k = 0; k < 3; ++k) out.normals[3 * i + k] = normal[k];
    }
  return out;
}

}  // namespace binpick
