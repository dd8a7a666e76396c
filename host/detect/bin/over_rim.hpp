// What reaches into the bin over its rim from outside: a robot arm, a hose, a part hanging over
// the rim. Standing higher than the rim, such a thing is the highest thing over the bin's
// interior and took the highest points, though nothing on it is in the bin (docs/detect/bin.md,
// "Reaching in over the rim"; docs/decisions/2026-12-04-bin-over-rim.md). It is told from a
// pile heaped over the rim by where it goes: it crosses a side of the rim the bin fit saw and
// goes on beyond it, while what the bin holds stays over the bin's footprint.
//
// The pixels over the rim (kernels/scene_mask_shared.h, bp_over_rim_class) beyond a side seen
// are grown, over neighbouring pixels that are over the rim too and within max_step of each
// other's height, into the pixels over the footprint they are joined to; missing depth (a hole
// in the arm's face) is crossed for up to max_gap pixels at the height last seen. The detector
// keeps the pixels reached out of the highest points, crops and votes, as it keeps the rim out.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "host/detect/bin/bin_fit.hpp"
#include "host/detect/bin/bin_planes.hpp"
#include "host/detect/scene/depth_to_points.hpp"
#include "host/runtime/cl/cl_buffer.hpp"
#include "kernels/scene_mask_shared.h"

namespace binpick {

// The test's form for a found bin: over the rim means more than `clearance` mm above it, and
// beyond the footprint more than `clearance` mm outside the interior's walls (so the rim tube
// itself is neither). Only the sides the fit saw (not BinFit::unseen_walls) give seeds.
// InputError for a bin not found or a non-finite value.
bp_over_rim over_rim_test(const BinFit& bin, double clearance);

struct OverRimClasses {
  std::vector<std::uint8_t> classes;  // BP_OVER_RIM_* a pixel
  std::vector<float> heights;         // the point's height in the bin's frame (0 without data)
  std::size_t beyond = 0;             // pixels of class BP_OVER_RIM_OUT
};

// Routine: the kernel over_rim_classes over n float4 points on the device. The classes and
// heights are read back only when some pixel is beyond a side (beyond > 0; otherwise both are
// left empty: nothing reaches in, the usual case).
OverRimClasses over_rim_classes(ocl::Device& dev, const ocl::Buffer<float>& points,
                                std::size_t n, const bp_over_rim& test);
// Reference: the same predicate in plain C++; equal byte for byte and bit for bit.
OverRimClasses over_rim_classes_reference(const PointImage& points, const bp_over_rim& test);

// The pixels joined to a pixel beyond a side (1; the others 0): the flood described above, in
// 4-neighbour steps. InputError when the sizes do not match.
std::vector<std::uint8_t> reaching_in(const OverRimClasses& c, std::uint32_t width,
                                      std::uint32_t height, float max_step, std::uint32_t max_gap);

// Below the rim such a thing goes on (an arm's end face slopes down into the pile) at heights a
// part can have: its faces are followed instead. The planes of the reached pixels with data
// (at most about 20000 of them on a grid; sequential RANSAC, bin_planes.hpp, within tol),
// most supported first; none when fewer than 50 pixels were reached.
std::vector<FoundPlane> reaching_planes(ocl::Device& dev, const std::vector<float>& xyzw,
                                        std::uint32_t width, std::uint32_t height,
                                        const std::vector<std::uint8_t>& reached, float tol);

// Grows `reached` along each plane: from a reached pixel within tol of it over neighbouring
// pixels within tol of it too (4-neighbour steps), crossing up to max_gap missing pixels.
void follow_planes(const std::vector<float>& xyzw, std::uint32_t width, std::uint32_t height,
                   const std::vector<FoundPlane>& planes, float tol, std::uint32_t max_gap,
                   std::vector<std::uint8_t>& reached);

}  // namespace binpick
