// The compute pass over the part-id atlas (shaders/bin_coverage.comp, see bin_atlas.hpp):
// per part, the pixels it covers when drawn alone and their bounding box in the image.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "synth/render/part_pixels.hpp"
#include "host/runtime/vk/vk_compute.hpp"

namespace binpick {

// The push constant block of bin_coverage.comp.
struct CoverageParams {
  std::uint32_t width = 0, height = 0;  // of the atlas region, row-major without padding
  std::uint32_t instance_count = 0;     // ids above it are ignored
};

class CoverageStage {
 public:
  explicit CoverageStage(vkrt::Context& ctx);
  // atlas: uint a pixel (part + 1, 0 none); shifts: 2 int a part, image pixel = atlas pixel +
  // shift. Accumulates into `parts` (several batches may add to the same buffers).
  void run(const vkrt::Buffer& atlas, const vkrt::Buffer& shifts, const PartPixelBuffers& parts,
           const CoverageParams& params);

 private:
  vkrt::ComputeProgram program_;
};

// Routine: bin_coverage.comp on the shared device, one atlas, fresh counters.
PartPixels coverage_counts(const std::vector<std::uint32_t>& atlas,
                           const std::vector<std::array<int, 2>>& shifts, const CoverageParams& params);
// Reference: the same in plain C++.
PartPixels coverage_counts_reference(const std::vector<std::uint32_t>& atlas,
                                     const std::vector<std::array<int, 2>>& shifts,
                                     const CoverageParams& params);

}  // namespace binpick
