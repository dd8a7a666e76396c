#include "host/tune/tune_table.hpp"

#include <fmt/format.h>

#include "host/core/atomic_file.hpp"

namespace binpick {

std::string tune_table_header() {
  return fmt::format("{:>3} {:>2} {:<16} {:>5} {:>6} {:>5} {:>5} {:>4} {:>4}  {:>6} {:>6} {:>6} "
                     "{:>6} {:>8} {:>6}\n",
                     "#", "rd", "varied", "ref", "clDist", "clAng", "excl", "angS", "disS",
                     "top", "strTop", "all", "strAll", "ms/hyp", "budget");
}

std::string tune_table_row(const TuneRow& r, bool best) {
  const DetectParams& d = r.point.detect;
  const TuneScore& s = r.score;
  return fmt::format("{:>3} {:>2} {:<16} {:>5.3g} {:>6.3g} {:>5.3g} {:>5.3g} {:>4} {:>4}  {:>5.1f}% "
                     "{:>5.1f}% {:>5.1f}% {:>5.1f}% {:>8.1f} {:>6}{}\n",
                     r.index, r.round, r.axis, d.ref_ratio, d.cluster_distance, d.cluster_angle,
                     d.exclusion_ratio, r.point.angle_steps, r.point.distance_steps, 100 * s.top,
                     100 * s.strict_top, 100 * s.all, 100 * s.strict_all, s.ms_per_hypothesis,
                     r.within_budget ? "yes" : "over", best ? "  <- best" : "");
}

void write_tune_csv(const std::filesystem::path& path, const std::vector<TuneRow>& rows,
                    std::size_t best) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "index,round,axis,ref_ratio,cluster_distance,cluster_angle,exclusion_ratio,"
           "angle_steps,distance_steps,top,all,strict_top,strict_all,ms_per_hypothesis,"
           "within_budget,best\n";
    for (const TuneRow& r : rows) {
      const DetectParams& d = r.point.detect;
      const TuneScore& s = r.score;
      out << fmt::format("{},{},{},{},{},{},{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.3f},{},{}\n",
                         r.index, r.round, r.axis, d.ref_ratio, d.cluster_distance,
                         d.cluster_angle, d.exclusion_ratio, r.point.angle_steps,
                         r.point.distance_steps, s.top, s.all, s.strict_top, s.strict_all,
                         s.ms_per_hypothesis, r.within_budget ? 1 : 0, r.index == best ? 1 : 0);
    }
  });
}

}  // namespace binpick
