// What the models detecting in one depth image share (`detect` with several models): the scene
// prepared from it (points and low-pass range image: nothing of a model in them) and the bins
// fitted in it, so that the second model neither prepares the image nor fits its bin again. Each
// model still gets its own low-pass buffer, which its region mask rewrites (bin_region.hpp), so
// a model's detections are exactly those it finds alone.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "host/detect/bin/bin_fit.hpp"
#include "host/detect/scene/scene_prepare.hpp"

namespace binpick {

class SharedScene {
 public:
  // The prepared scene for one model: prepared here on the first call (its timings then carry
  // the preparation's stages; later calls' carry none), a copy sharing the points afterwards.
  PreparedScene scene_for_model(ocl::Device& dev, DepthView depth, const bp_camera& cam,
                                const ScenePrepOptions& opt);
  // The bin fitted with this spec ("auto", "W,D,H") for a part of this diameter (the bin's
  // least height and width follow from it), if a model fitted it.
  const BinFit* bin(const std::string& spec, double part_diameter) const;
  void keep_bin(const std::string& spec, double part_diameter, const BinFit& fit);

 private:
  std::optional<PreparedScene> prepared_;
  std::vector<std::pair<std::pair<std::string, double>, BinFit>> bins_;
};

}  // namespace binpick
