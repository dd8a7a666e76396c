// The region detection may use in one depth image (--roi, --bin): fits the bin if one is asked
// for (bin_fit.hpp), builds the "may be used" mask on the device (scene_mask.hpp) and recomputes
// the scene's low-pass range image from the kept points only, so that the highest points, the
// crops and the votes see nothing outside the region. Verification still sees every measured
// point (a pose that runs into the bin's wall is seen through, as it should be).
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>

#include "host/core/timing.hpp"
#include "host/detect/bin/bin_fit.hpp"
#include "host/detect/params/bin_spec.hpp"
#include "host/detect/bin/scene_mask.hpp"
#include "host/detect/scene/scene_prepare.hpp"

namespace binpick {

struct RegionSetup {
  std::optional<RoiSpec> roi;
  BinSpec bin;
  double margin = 0;  // mm, the bin's walls and rim kept out by this much
  double above = 0;   // mm, the interior reaches this far over the rim
  double min_height = 0;  // mm, a shallower "bin" is not one (BinFitOptions::min_height)
  double min_side = 0;    // mm, nor a narrower one (BinFitOptions::min_side)
  double noise = 0;       // mm, the image's depth noise (BinFitOptions::noise)
  // Keep the floor out: points less than the bin fit's plane tolerance above a fitted floor
  // are not used (bin_interior_box); false: the floor stays, from margin below it.
  bool clear_floor = true;
  // Points the sensor sees through one of the fitted walls (between a wire-mesh basket's bars)
  // are kept out as the walls are; true: they stay in (scene_mask.hpp, BinWalls).
  bool keep_through_walls = false;
  // What reaches into the bin over its rim from outside (over_rim.hpp: a robot arm) is kept
  // out as the rim is; true: it stays in. over_rim_gap (mm): the holes in its depth crossed.
  bool keep_over_rim = false;
  double over_rim_gap = 0;
  // ... but never more than this (mm): half the part's thinnest extent, so that a sheet thinner
  // than the tolerance (1.5 mm against 3 to 6 mm at 1 to 2 m) lying on the floor stays in.
  double floor_clearance_cap = std::numeric_limits<double>::infinity();
  bool wanted() const { return roi.has_value() || bin.mode != BinSpec::Mode::none; }
};

struct SceneRegionMask {
  std::optional<ocl::Buffer<std::uint8_t>> mask;  // none: the whole image may be used
  std::optional<BinFit> bin;                      // when one was asked for
  std::string report;   // for --verbose: the bin found and the pixels kept
  std::string warning;  // the bin asked for was not found (the whole image is used, or the ROI)
  std::size_t kept = 0;  // pixels the mask keeps (when there is one)
  std::size_t over_rim = 0;  // pixels of them left out as reaching in over the rim (over_rim.hpp)
};

// On a scene prepared on the device (prepare_scene): its `filtered` buffer is replaced by the
// low-pass of the kept points when a mask is made, and written from all points when no mask is
// made and prepare_scene left it out (ScenePrepOptions::lowpass). Appends "bin fit", "mask" and
// "lowpass" (when it computes one) to timings.
// known_bin: the bin fitted in this image with setup's spec and min_height before (another model
// detecting in it, shared_scene.hpp), used instead of fitting again.
SceneRegionMask apply_region(PreparedScene& scene, const RegionSetup& setup, int lowpass_radius,
                             StageTimings* timings = nullptr, const BinFit* known_bin = nullptr);

}  // namespace binpick
