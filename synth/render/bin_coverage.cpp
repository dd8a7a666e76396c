#include "synth/render/bin_coverage.hpp"

#include <string>

#include "host/core/error.hpp"

namespace binpick {
namespace {

static_assert(sizeof(CoverageParams) == 12, "push constant block of bin_coverage.comp");

void check(const std::vector<std::uint32_t>& atlas, const std::vector<std::array<int, 2>>& shifts,
           const CoverageParams& p) {
  if (atlas.size() != std::size_t(p.width) * p.height || shifts.size() != p.instance_count)
    throw InputError("coverage input does not match " + std::to_string(p.width) + " x " +
                     std::to_string(p.height) + " pixels and " + std::to_string(p.instance_count) +
                     " parts");
}

}  // namespace

CoverageStage::CoverageStage(vkrt::Context& ctx)
    : program_(ctx, "bin_coverage.comp", 4, sizeof(CoverageParams)) {}

void CoverageStage::run(const vkrt::Buffer& atlas, const vkrt::Buffer& shifts,
                        const PartPixelBuffers& parts, const CoverageParams& params) {
  program_.run({&atlas, &shifts, &parts.counts(), &parts.boxes()}, &params,
               (params.width + 15) / 16, (params.height + 15) / 16);
}

PartPixels coverage_counts(const std::vector<std::uint32_t>& atlas,
                           const std::vector<std::array<int, 2>>& shifts, const CoverageParams& p) {
  check(atlas, shifts, p);
  auto& ctx = vkrt::Context::shared();
  auto atlas_buffer = vkrt::Buffer::from(ctx, std::span<const std::uint32_t>(atlas));
  auto shift_buffer = vkrt::Buffer::from(ctx, std::span<const std::array<int, 2>>(shifts));
  PartPixelBuffers parts(ctx, p.instance_count);
  CoverageStage(ctx).run(atlas_buffer, shift_buffer, parts, p);
  return parts.read();
}

PartPixels coverage_counts_reference(const std::vector<std::uint32_t>& atlas,
                                     const std::vector<std::array<int, 2>>& shifts,
                                     const CoverageParams& p) {
  check(atlas, shifts, p);
  PartPixels out(p.instance_count);
  for (std::uint32_t y = 0; y < p.height; ++y)
    for (std::uint32_t x = 0; x < p.width; ++x) {
      const std::uint32_t id = atlas[std::size_t(y) * p.width + x];
      if (id == 0 || id > p.instance_count) continue;
      out.add(id - 1, int(x) + shifts[id - 1][0], int(y) + shifts[id - 1][1]);
    }
  return out;
}

}  // namespace binpick
