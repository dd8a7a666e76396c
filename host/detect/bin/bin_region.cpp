#include "host/detect/bin/bin_region.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/detect/bin/over_rim.hpp"
#include "host/detect/scene/scene_lowpass.hpp"

namespace binpick {

namespace {

// The scene's low-pass range image when prepare_scene left it out (ScenePrepOptions::lowpass),
// over all its points: no mask was made.
void lowpass_if_missing(PreparedScene& scene, int lowpass_radius, StageTimings* timings) {
  if (scene.has_lowpass) return;
  if (!scene.device) throw InputError("apply_region needs a scene on the device");
  Stopwatch clock;
  ocl::Device& dev = *scene.device->dev;
  enqueue_lowpass_depth(dev, scene.device->points, scene.width, scene.height, lowpass_radius,
                        scene.device->filtered);
  ocl::finish(dev);
  scene.has_lowpass = true;
  if (timings) timings->push_back({"lowpass", clock.lap()});
}

// Clears from the mask m what reaches into the bin over its rim (over_rim.hpp); how many pixels
// it kept before. Over the rim and beyond the walls by max(3 tolerances, the margin): the rim
// and the pile's top at its height stay; neighbours join within that or over_rim_gap mm of
// height, whichever is more, and a hole of up to over_rim_gap mm (in pixels at the rim's
// distance) is crossed.
std::size_t keep_over_rim_out(ocl::Device& dev, const PreparedScene& scene, const BinFit& bin,
                              const RegionSetup& setup, std::vector<std::uint8_t>& m) {
  const double clearance = std::max(3 * bin.tol, setup.margin);
  const std::size_t n = std::size_t(scene.width) * scene.height;
  const OverRimClasses c =
      over_rim_classes(dev, scene.device->points, n, over_rim_test(bin, clearance));
  if (c.beyond == 0) return 0;
  // A step between neighbours as large as a hole: an edge seen edge on (a vertical end face
  // from above) jumps by more than the clearance in one pixel.
  const double step = std::max(clearance, setup.over_rim_gap);
  // The rim's distance over the floor's centre (up faces the camera).
  const double rim_z = std::max(1.0, (bin.origin + bin.interior.z() * bin.axes.col(2)).z());
  const double focal = 0.5 * (scene.camera.fx + scene.camera.fy);
  const auto gap = std::uint32_t(std::clamp(std::ceil(setup.over_rim_gap * focal / rim_z), 0.0,
                                            double(std::max(scene.width, scene.height))));
  std::vector<std::uint8_t> reached =
      reaching_in(c, scene.width, scene.height, float(step), gap);
  // Below the rim it goes on along its faces (over_rim.hpp); only when it reached in at all.
  bool in = false;
  for (std::size_t i = 0; i < n && !in; ++i) in = reached[i] && c.classes[i] == BP_OVER_RIM_IN;
  if (in) {
    const std::vector<float> xyzw = scene.device->points.read(dev, 4 * n);
    const float tol = float(bin.tol);
    follow_planes(xyzw, scene.width, scene.height,
                  reaching_planes(dev, xyzw, scene.width, scene.height, reached, tol), tol, gap,
                  reached);
  }
  std::size_t cleared = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (reached[i] && m[i]) m[i] = 0, ++cleared;
  return cleared;
}

}  // namespace

SceneRegionMask apply_region(PreparedScene& scene, const RegionSetup& setup, int lowpass_radius,
                             StageTimings* timings, const BinFit* known_bin) {
  SceneRegionMask out;
  if (!setup.wanted()) {
    lowpass_if_missing(scene, lowpass_radius, timings);
    return out;
  }
  if (!scene.device) throw InputError("apply_region needs a scene on the device");
  ocl::Device& dev = *scene.device->dev;
  const std::size_t n = std::size_t(scene.width) * scene.height;
  Stopwatch clock;
  SceneRegion region;
  if (setup.bin.mode != BinSpec::Mode::none) {
    BinFitOptions bo;
    bo.spec = setup.bin;
    bo.min_height = setup.min_height;
    bo.min_side = setup.min_side;
    bo.noise = setup.noise;
    out.bin = known_bin ? *known_bin
                        : fit_bin(dev,
                                  sample_points(dev, scene.device->points, scene.width,
                                                scene.height, scene.valid_pixels),
                                  bo);
    out.report = describe(*out.bin);
    if (out.bin->found) {
      const bool clear = setup.clear_floor && out.bin->floor_plane;
      region.bin = bin_interior_box(*out.bin, setup.margin, setup.above,
                                    clear ? std::min(out.bin->tol, setup.floor_clearance_cap)
                                          : -1);
      if (!setup.keep_through_walls) region.walls = bin_walls(*out.bin);
    } else {
      out.warning = fmt::format("no bin found ({}); detecting in the whole image{}", out.bin->why,
                                setup.roi && setup.roi->frame == RoiSpec::Frame::bin
                                    ? ", without the bin-frame --roi"
                                    : "");
    }
    if (timings) timings->push_back({"bin fit", clock.lap()});
  }
  if (setup.roi && (setup.roi->frame == RoiSpec::Frame::camera || region.bin))
    region.roi = roi_box(*setup.roi, out.bin ? &*out.bin : nullptr);
  if (!region.active()) {
    lowpass_if_missing(scene, lowpass_radius, timings);
    return out;
  }

  out.mask.emplace(scene_mask(dev, scene.device->points, n, region));
  std::vector<std::uint8_t> m = out.mask->read(dev);
  if (timings) timings->push_back({"mask", clock.lap()});
  if (region.bin && !setup.keep_over_rim) {
    out.over_rim = keep_over_rim_out(dev, scene, *out.bin, setup, m);
    if (out.over_rim > 0) {
      out.mask->write(dev, std::span<const std::uint8_t>(m));
      out.report += fmt::format("; {} pixels over the rim reaching in from outside left out",
                                out.over_rim);
    }
    if (timings) timings->push_back({"over rim", clock.lap()});
  }
  out.kept = std::size_t(std::count(m.begin(), m.end(), std::uint8_t(1)));
  enqueue_lowpass_depth(dev, scene.device->points, scene.width, scene.height, lowpass_radius,
                        scene.device->filtered, &*out.mask);
  ocl::finish(dev);
  scene.has_lowpass = true;
  if (timings) timings->push_back({"lowpass", clock.lap()});
  return out;
}

}  // namespace binpick
