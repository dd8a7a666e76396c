// bench.md: one table per question a user asks (how fast per stage, how close to the machine,
// how it scales, how it compares with OpenCV), each with the units in its header.
#include <algorithm>
#include <sstream>

#include <fmt/format.h>

#include "bench/lib/bench_report.hpp"
#include "bench/lib/stage_bench.hpp"
#include "bench/lib/throughput.hpp"

namespace binpick::bench {
namespace {

std::string pct(double f) { return fmt::format("{:.0f} %", 100 * f); }
std::string pct1(double f) { return fmt::format("{:.1f} %", 100 * f); }
std::string si(double v) {
  if (v >= 1e9) return fmt::format("{:.2f} G", v / 1e9);
  if (v >= 1e6) return fmt::format("{:.1f} M", v / 1e6);
  if (v >= 1e3) return fmt::format("{:.1f} k", v / 1e3);
  return fmt::format("{:.0f}", v);
}
std::string ratio_label(double r) { return fmt::format("{:g} %", 100 * r); }

// The paper's times per hypothesis (section IV) at its two operating points.
std::string paper_ms(double ratio) {
  if (ratio == 0.2) return "726";
  if (ratio == 0.02) return "70";
  return "";
}

void machine(std::ostream& os, const BenchResult& r) {
  const auto& m = r.machine;
  os << fmt::format(
      "# binpick benchmark\n\n{} — part {}, scene {}; medians of {} runs; whole bench {:.0f} s.\n\n"
      "| device | |\n|---|---|\n| OpenCL | {} |\n| Vulkan | {} |\n| cores | {} |\n"
      "| memory-bound peak (stream triad) | {:.1f} GB/s |\n"
      "| compute-bound peak (FMA chains) | {:.1f} GFLOP/s |\n"
      "| integer peak | {:.1f} G ops/s |\n"
      "| random-gather peak, table out of cache | {:.0f} M lookups/s |\n"
      "| random-gather peak, table in L2 (the yardstick of voting) | {:.0f} M lookups/s |\n\n",
      m.date, r.part, r.scene, r.repeats, r.seconds, m.opencl, m.vulkan, m.cores, m.stream_gb_s,
      m.fma_gflop_s, m.int_gop_s, m.gather_mlookup_s, m.gather_cached_mlookup_s);
}

void stages(std::ostream& os, const BenchResult& r) {
  os << "## Detection, ms per hypothesis\n\n"
        "| reference points | hypotheses | preparation | highest points | voting | clustering | "
        "total | paper | precision top / all (10 %, 15°) | (5 %, 5°) |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& d : r.detect)
    os << fmt::format("| {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | **{:.2f}** | {} | {} / {} | {} / {} |\n",
                      ratio_label(d.ref_ratio), d.hypotheses, d.prepare_ms, d.hypotheses_ms,
                      d.vote_ms, d.cluster_ms, d.total_ms, paper_ms(d.ref_ratio),
                      pct(d.precision_top), pct(d.precision_all), pct(d.precision_top_strict),
                      pct(d.precision_all_strict));
  os << "\nEvery stage (ms per hypothesis; the image-wide stages are shared by its hypotheses):\n\n"
        "| stage |";
  for (const auto& d : r.detect) os << " " << ratio_label(d.ref_ratio) << " |";
  os << "\n|---|";
  for (std::size_t i = 0; i < r.detect.size(); ++i) os << "---|";
  os << "\n";
  if (!r.detect.empty())
    for (std::size_t s = 0; s < r.detect[0].stages.size(); ++s) {
      os << "| " << r.detect[0].stages[s].stage << " |";
      for (const auto& d : r.detect)
        os << fmt::format(" {:.3f} |", s < d.stages.size() ? d.stages[s].ms_per_hyp : 0.0);
      os << "\n";
    }
  // Where the next gain must come from: the stage taking most of a hypothesis' time.
  for (const auto& d : r.detect) {
    if (d.stages.empty() || !(d.total_ms > 0)) continue;
    const auto top = std::max_element(d.stages.begin(), d.stages.end(),
                                      [](const auto& a, const auto& b) { return a.ms_per_hyp < b.ms_per_hyp; });
    os << fmt::format("\nThe limit at {} reference points: {}, {:.1f} of {:.1f} ms a hypothesis ({}).",
                      ratio_label(d.ref_ratio), top->stage, top->ms_per_hyp, d.total_ms,
                      pct(top->ms_per_hyp / d.total_ms));
  }
  os << "\n\n";
}

// The paper's image next to the real sensor's: what an image costs at each size, and the stages
// that grow with the pixels.
void real_size(std::ostream& os, const BenchResult& r) {
  if (!r.real || r.detect.empty()) return;
  const DetectMeasure& paper = r.detect.front();
  const DetectMeasure& real = *r.real;
  os << "## The real sensor's size\n\nThe same bins seen by " << r.real_scene
     << ", detected at the defaults, next to the paper's view at the first reference ratio.\n\n"
        "| scene | reference points | hypotheses per image | ms per image | ms per hypothesis | "
        "precision top / all (10 %, 15°) |\n|---|---|---|---|---|---|\n";
  for (const DetectMeasure* d : {&paper, &real})
    os << fmt::format("| {} | {} | {:.1f} | **{:.0f}** | {:.1f} | {} / {} |\n",
                      d == &paper ? r.scene : r.real_scene, ratio_label(d->ref_ratio),
                      double(d->hypotheses) / double(std::max<std::size_t>(d->images, 1)),
                      d->ms_per_image, d->total_ms, pct(d->precision_top), pct(d->precision_all));
  os << "\nms per image, stage by stage:\n\n| stage | paper's view | real size |\n|---|---|---|\n";
  // Stages match by name without their detail ("prerank (10 highest points)").
  auto name = [](const std::string& stage) { return stage.substr(0, stage.find(" (")); };
  auto per_image = [&](const DetectMeasure& d, const std::string& stage) {
    for (const auto& s : d.stages)
      if (name(s.stage) == name(stage))
        return s.ms_per_hyp * double(d.hypotheses) / double(std::max<std::size_t>(d.images, 1));
    return 0.0;
  };
  for (const auto& s : real.stages)
    os << fmt::format("| {} | {:.1f} | {:.1f} |\n", s.stage, per_image(paper, s.stage),
                      per_image(real, s.stage));
  os << "\n";
}

void rates(std::ostream& os, const BenchResult& r) {
  os << "## Throughput against the machine\n\n"
        "Work per hypothesis counted, divided by the stage's time. Fractions compare with the "
        "peaks above: pair features at ~"
     << kFeatureFlopsPerPair
     << " flops each against the FMA peak; hash lookups + votes (one data-dependent access "
        "each) against the gather peak; accumulator cells scanned (4 bytes) against the "
        "stream bandwidth.\n\n"
        "| reference points | pairs / hyp | pair features/s | of FMA peak | lookups/s | votes/s | "
        "of gather peak | cells/s | of stream peak |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& d : r.detect) {
    const Throughput t = throughput(d, r.machine);
    os << fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", ratio_label(d.ref_ratio),
                      si(d.counts.pairs), si(t.pairs_per_s), pct1(t.features_of_fma_peak),
                      si(t.lookups_per_s), si(t.votes_per_s), pct1(t.voting_of_gather_peak),
                      si(t.cells_per_s), pct1(t.peaks_of_stream_peak));
  }
  os << "\n";
}

void synth_and_train(std::ostream& os, const BenchResult& r) {
  os << "## Synthetic bins, seconds per bin\n\n| bin | physics | rendering | decomposition | "
        "writing | total |\n|---|---|---|---|---|---|\n";
  std::vector<double> physics, render, total;
  for (const auto& b : r.synth) {
    if (b.physics_s < 0) {
      os << fmt::format("| {} | made by an earlier run without a record | | | | |\n", b.bin);
      continue;
    }
    const double sum = b.physics_s + b.render_s + b.decompose_s + b.write_s;
    physics.push_back(b.physics_s), render.push_back(b.render_s), total.push_back(sum);
    os << fmt::format("| {}{} | {:.1f} | {:.2f} | {:.3f} | {:.2f} | {:.1f} |\n", b.bin,
                      b.measured_now ? "" : " (earlier run)", b.physics_s, b.render_s,
                      b.decompose_s, b.write_s, sum);
  }
  if (!total.empty())
    os << fmt::format("| median | {:.1f} | {:.2f} | | | {:.1f} |\n", median(physics),
                      median(render), median(total));
  os << "\n";
  os << fmt::format("## Model\n\nTraining: {} points, {} table entries, **{:.0f} ms** (voxel {} of "
                    "the diameter).\n\n",
                    r.train.points, r.train.entries, r.train.ms, r.train.voxel_ratio);
}

// The exponent in words, so a reader need not think in logs.
std::string growth(double k) {
  if (k < 0.8) return "sub-linear";
  if (k < 1.2) return "about linear";
  if (k < 1.8) return "between linear and quadratic";
  if (k < 2.2) return "about quadratic";
  return "faster than quadratic";
}

void scaling(std::ostream& os, const BenchResult& r) {
  os << "## Scaling\n\nExponent k of time ~ size^k, least squares on a log-log scale.\n\n";
  for (const auto& s : r.scaling) {
    const bool entries = std::any_of(s.points.begin(), s.points.end(),
                                     [](const ScalingPoint& p) { return p.extra > 0; });
    os << fmt::format("### {} (k = {:.2f}: {})\n\n| {} | {} |{} ms |\n|---|---|{}---|\n", s.name,
                      s.exponent, growth(s.exponent), s.x_label, s.size_label,
                      entries ? " table entries |" : "", entries ? "---|" : "");
    for (const auto& p : s.points)
      os << fmt::format("| {:g} | {:.0f} |{} {:.3f} |\n", p.x, p.size,
                        entries ? fmt::format(" {:.0f} |", p.extra) : "", p.ms);
    os << "\n";
  }
  os << "The model sweep retrains at each voxel size; the scene is subsampled at the same voxel, "
        "so its points change with the model's.\n\n";
}

void opencv(std::ostream& os, const BenchResult& r) {
  const auto& c = r.opencv;
  os << "## OpenCV's PPF3DDetector side by side\n\n";
  if (!c.ran) {
    os << "Not run: " << c.why_not << ".\n";
    return;
  }
  os << fmt::format(
      "OpenCV {} (`{}`), the same model points, crops, parameters and ground truth. Times: "
      "binpick's voting + clustering vs OpenCV's match() per crop. Training: binpick {:.0f} ms, "
      "OpenCV {:.0f} ms.\n\n| reference points | crops | binpick ms | OpenCV ms | OpenCV / "
      "binpick | binpick top / all | OpenCV top / all |\n|---|---|---|---|---|---|---|\n",
      c.version, c.runner, c.binpick_train_ms, c.opencv_train_ms);
  for (const auto& s : c.sides)
    os << fmt::format("| {} | {} | {:.2f} | {:.2f} | **{:.1f}x** | {} / {} | {} / {} |\n",
                      ratio_label(s.ref_ratio), s.crops, s.binpick_ms, s.opencv_ms,
                      s.binpick_ms > 0 ? s.opencv_ms / s.binpick_ms : 0.0, pct(s.binpick_top),
                      pct(s.binpick_all), pct(s.opencv_top), pct(s.opencv_all));
  os << "\nPrecision at (10 %, 15°): top = the best-voted crop of each image, all = every crop "
        "(a crop without a pose counts as wrong).\n";
}

}  // namespace

std::string bench_markdown(const BenchResult& r) {
  std::ostringstream os;
  machine(os, r);
  stages(os, r);
  real_size(os, r);
  rates(os, r);
  synth_and_train(os, r);
  scaling(os, r);
  opencv(os, r);
  return os.str();
}

}  // namespace binpick::bench
