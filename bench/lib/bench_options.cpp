#include "bench/lib/bench_options.hpp"

#include <cmath>

#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick::bench {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw InputError(message);
}

void check_fractions(const std::vector<double>& v, const char* option, double hi) {
  require(!v.empty(), fmt::format("{} needs at least one value", option));
  for (double x : v)
    require(std::isfinite(x) && x > 0 && x <= hi,
            fmt::format("{} {} must be in (0, {}]", option, x, hi));
}

}  // namespace

BenchOptions quick_options(BenchOptions o) {
  o.bins = 1;
  o.objects = 30;
  o.width = 800;
  o.height = 450;
  o.real_width = 1032;
  o.real_height = 772;
  o.repeats = 1;
  o.scaling_ref_ratios = {0.05, 0.2, 1.0};
  o.scaling_crop_fractions = {0.5, 1.0};
  o.scaling_voxel_ratios = {0.05, 0.08};
  o.quick_peaks = true;
  return o;
}

void check(const BenchOptions& o) {
  require(o.bins >= 1 && o.bins <= 1000, fmt::format("--bins {} must be in [1, 1000]", o.bins));
  require(o.objects >= 1 && o.objects <= 5000,
          fmt::format("--objects {} must be in [1, 5000]", o.objects));
  require(o.repeats >= 1 && o.repeats <= 100,
          fmt::format("--repeats {} must be in [1, 100]", o.repeats));
  require(o.width >= 16 && o.height >= 16 && o.width <= 8192 && o.height <= 8192,
          fmt::format("image size {} x {} must be within 16 .. 8192 pixels", o.width, o.height));
  const auto in_range = [](std::uint32_t v) { return v >= 16 && v <= 8192; };
  require((o.real_width == 0 && o.real_height == 0) ||
              (in_range(o.real_width) && in_range(o.real_height)),
          fmt::format("--real-size {} x {} must be within 16 .. 8192 pixels, or off",
                      o.real_width, o.real_height));
  require(!o.out.empty(), "--out must name a directory");
  check_fractions(o.ref_ratios, "--ref-ratios", 1.0);
  check_fractions(o.scaling_ref_ratios, "scaling reference ratios", 1.0);
  check_fractions(o.scaling_crop_fractions, "scaling crop fractions", 1.0);
  check_fractions(o.scaling_voxel_ratios, "scaling voxel ratios", 1.0);
  check_train_params(o.train);
  DetectParams d = o.detect;
  for (double r : o.ref_ratios) d.ref_ratio = r, binpick::check(d);
}

}  // namespace binpick::bench
