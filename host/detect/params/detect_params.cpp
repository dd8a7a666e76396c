#include "host/detect/params/detect_params.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/detect/params/bin_spec.hpp"
#include "host/detect/params/param_table.hpp"

namespace binpick {
namespace {

bool in_range(double v, const ParamRange& r) {
  if (!std::isfinite(v)) return false;
  if (r.or_zero && v == 0) return true;
  return (r.lo_open ? v > r.lo : v >= r.lo) && v <= r.hi;
}

}  // namespace

std::optional<ParamProblem> find_param_problem(const DetectParams& p, BinSpec* parsed_bin) {
  for (const ParamInfo& info : detect_param_table()) {
    if (is_flag(info) || is_text(info)) continue;
    const double v = number_of(info, p);
    if (!in_range(v, info.range)) return ParamProblem{info.name, v, range_text(info), {}};
  }
  std::optional<RoiSpec> roi;
  try {
    roi = parse_roi(p.roi);
  } catch (const InputError& e) {
    return ParamProblem{"roi", 0, "", e.what()};
  }
  BinSpec bin;
  try {
    bin = parse_bin(p.bin);
  } catch (const InputError& e) {
    return ParamProblem{"bin", 0, "", e.what()};
  }
  if (parsed_bin) *parsed_bin = bin;
  if (p.instances > 0 && (p.stop_at_confident || p.budget_ms > 0))
    return ParamProblem{"instances", double(p.instances), "",
                        "--instances ranks every hypothesis' poses together: it does not go with "
                        "--stop-at-confident or --budget-ms, which take them one at a time"};
  if (roi && roi->frame == RoiSpec::Frame::bin && bin.mode == BinSpec::Mode::none &&
      p.bin_pose.empty())
    return ParamProblem{
        "roi", 0, "",
        fmt::format("'{}' is in the bin's frame: it needs --bin auto, --bin W,D,H or --bin-pose",
                    p.roi)};
  return std::nullopt;
}

std::string describe(const ParamProblem& bad) {
  if (!bad.message.empty()) return bad.message;
  return fmt::format("{} must be in {}", bad.value, bad.range);
}

BinSpec check(const DetectParams& p) {
  BinSpec bin;
  if (const auto bad = find_param_problem(p, &bin))
    throw InputError(fmt::format("detection parameter {} {}", bad->name, describe(*bad)));
  return bin;
}

std::size_t hypotheses_sought(const DetectParams& p) {
  if (p.instances > 0) return std::max(p.hypotheses, p.instances);
  return std::size_t(p.hypotheses) + p.more_hypotheses;
}

}  // namespace binpick
