#include "synth/bop_visibility.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "host/core/error.hpp"
#include "host/formats/bop/depth_distance.hpp"

namespace binpick {

BopVisibility bop_visibility(const PartSilhouette& part, const BopDepthImage& depth,
                             const Eigen::Matrix3d& K, double delta, bool keep_pixels) {
  const std::size_t n = std::size_t(depth.width) * depth.height;
  if (!depth.raw || depth.raw->size() != n)
    throw InputError("BOP visibility: the depth image does not have " +
                     std::to_string(depth.width) + " x " + std::to_string(depth.height) + " pixels");
  if (part.pixels.size() != part.depth_mm.size())
    throw InputError("BOP visibility: " + std::to_string(part.pixels.size()) + " pixels and " +
                     std::to_string(part.depth_mm.size()) + " depths");
  BopVisibility out;
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  for (std::size_t i = 0; i < part.pixels.size(); ++i) {
    const std::uint32_t p = part.pixels[i];
    if (p >= n) throw InputError("BOP visibility: pixel " + std::to_string(p) + " is outside the image");
    const float model_z = part.depth_mm[i];
    if (!(model_z > 0)) continue;  // not on the silhouette (dist_gt > 0 fails)
    const std::uint32_t u = p % depth.width, v = p / depth.width;
    const std::uint16_t raw = (*depth.raw)[p];
    out.px_count_valid += raw > 0;
    // As the toolkit: both distances as float32, their difference against delta.
    const float model = float(bop::distance_of_depth(model_z, u, v, K));
    const double image_z = bop::depth_mm_of_raw(raw, depth.depth_scale);
    const float image = raw > 0 ? float(bop::distance_of_depth(image_z, u, v, K)) : 0.0f;
    if (!(raw == 0 || model - image <= float(delta))) continue;
    if (keep_pixels) out.visible.push_back(p);
    if (out.px_count_visib++ == 0) x0 = x1 = int(u), y0 = y1 = int(v);
    x0 = std::min(x0, int(u)), x1 = std::max(x1, int(u));
    y0 = std::min(y0, int(v)), y1 = std::max(y1, int(v));
  }
  if (out.px_count_visib > 0) out.bbox_visib = {x0, y0, x1 - x0, y1 - y0};
  return out;
}

}  // namespace binpick
