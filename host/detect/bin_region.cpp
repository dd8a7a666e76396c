#include "host/detect/bin_region.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/detect/scene_lowpass.hpp"

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
  const std::vector<std::uint8_t> m = out.mask->read(dev);
  out.kept = std::size_t(std::count(m.begin(), m.end(), std::uint8_t(1)));
  if (timings) timings->push_back({"mask", clock.lap()});
  enqueue_lowpass_depth(dev, scene.device->points, scene.width, scene.height, lowpass_radius,
                        scene.device->filtered, &*out.mask);
  ocl::finish(dev);
  scene.has_lowpass = true;
  if (timings) timings->push_back({"lowpass", clock.lap()});
  return out;
}

}  // namespace binpick
