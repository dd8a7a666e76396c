#include "bench/lib/bench_run.hpp"

#include <chrono>
#include <ctime>
#include <ostream>
#include <thread>

#include <fmt/format.h>

#include "bench/lib/bench_dataset.hpp"
#include "bench/lib/machine_peak.hpp"
#include "bench/lib/opencv_compare.hpp"
#include "bench/lib/scaling_bench.hpp"
#include "bench/lib/stage_bench.hpp"
#include "host/runtime/cl/cl_device.hpp"
#include "host/core/timing.hpp"
#include "host/eval/metrics/eval_dataset.hpp"
#include "host/runtime/vk/vk_context.hpp"
#include "synth/pile_cache.hpp"

namespace binpick::bench {
namespace {

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

MachineInfo machine_info(const BenchOptions& o) {
  MachineInfo m;
  auto& dev = ocl::Device::shared();
  m.opencl = dev.description();
  m.vulkan = vkrt::Context::shared().description();
  m.cores = std::thread::hardware_concurrency();
  m.date = utc_now();
  PeakOptions po;
  po.quick = o.quick_peaks;
  const MachinePeak peak = measure_machine_peak(dev, po);
  m.stream_gb_s = peak.stream_gb_s;
  m.fma_gflop_s = peak.fma_gflop_s;
  m.gather_mlookup_s = peak.gather_glookup_s * 1e3;
  m.gather_cached_mlookup_s = peak.gather_cached_glookup_s * 1e3;
  m.int_gop_s = peak.int_gop_s;
  return m;
}

TrainMeasure measure_training(const Mesh& mesh, const BenchOptions& o, PpfModel* model) {
  std::vector<double> ms;
  *model = train_ppf_model(mesh, o.train);  // warm-up: builds the programs, first touch
  for (int r = 0; r < o.repeats; ++r) {
    Stopwatch clock;
    *model = train_ppf_model(mesh, o.train);
    ms.push_back(clock.lap());
  }
  return {o.train.voxel_ratio, model->cloud.points.size(), model->table.entries.size(), median(ms)};
}

}  // namespace

BenchRun run_bench(const Model& part, const BenchOptions& o, std::ostream& log) {
  check(o);
  const auto start = std::chrono::steady_clock::now();
  BenchRun run;
  BenchResult& r = run.result;
  r.part = describe(o.part);
  r.scene = fmt::format("{} x {}, {} parts, {} bins", o.width, o.height, o.objects, o.bins);
  r.repeats = o.repeats;

  log << "bench: peaks of the OpenCL device" << std::endl;
  r.machine = machine_info(o);
  log << fmt::format("  stream {:.1f} GB/s, FMA {:.1f} GFLOP/s, gather {:.0f} M lookups/s\n",
                     r.machine.stream_gb_s, r.machine.fma_gflop_s, r.machine.gather_mlookup_s);

  log << fmt::format("bench: scenes ({}) in {}", r.scene, dataset_dir(o).string()) << std::endl;
  PileCache piles;  // the real-size view drops the same piles
  r.synth = make_bench_dataset(part, o, false, &piles);

  log << "bench: training" << std::endl;
  PpfModel model;
  r.train = measure_training(part.mesh, o, &model);
  log << fmt::format("  {} points, {} entries, {:.0f} ms\n", r.train.points, r.train.entries,
                     r.train.ms);

  const auto scenes = load_bench_scenes(dataset_dir(o));
  const eval::Dataset dataset = eval::load_dataset(dataset_dir(o));
  std::vector<BenchCrop> crops;
  for (double ratio : o.ref_ratios) {
    log << fmt::format("bench: detection at {:g} % reference points", 100 * ratio) << std::endl;
    DetectParams p = o.detect;
    p.ref_ratio = ratio;
    StageRun stage = run_stages(model, p, scenes, dataset, o.repeats);
    log << fmt::format("  {:.2f} ms per hypothesis, precision top {:.0f} %, all {:.0f} %\n",
                       stage.measure.total_ms, 100 * stage.measure.precision_top,
                       100 * stage.measure.precision_all);
    r.detect.push_back(stage.measure);
    if (crops.empty()) crops = std::move(stage.crops);
  }

  if (o.real_width > 0) {
    r.real_scene = fmt::format("{} x {}, structured light, {:g} m, tilted {:g}°", o.real_width,
                               o.real_height, o.real_camera_height_mm / 1000,
                               o.real_camera_tilt_deg);
    log << fmt::format("bench: the same bins at the real size ({}) in {}", r.real_scene,
                       real_dataset_dir(o).string())
        << std::endl;
    make_bench_dataset(part, o, true, &piles);
    const StageRun real = run_stages(model, o.detect, load_bench_scenes(real_dataset_dir(o)),
                                     eval::load_dataset(real_dataset_dir(o)), o.repeats);
    log << fmt::format("  {:.0f} ms per image, precision top {:.0f} %\n", real.measure.ms_per_image,
                       100 * real.measure.precision_top);
    r.real = real.measure;
  }

  log << "bench: scaling" << std::endl;
  DetectParams p = o.detect;
  p.ref_ratio = o.ref_ratios.front();
  r.scaling.push_back(scale_with_ref_ratio(model, p, crops, o.scaling_ref_ratios, o.repeats));
  r.scaling.push_back(scale_with_scene_points(model, p, crops, o.scaling_crop_fractions, o.repeats));
  for (auto& s : scale_with_model_points(part.mesh, o, scenes)) r.scaling.push_back(std::move(s));

  log << "bench: OpenCV's PPF3DDetector on the same crops" << std::endl;
  r.opencv = compare_with_opencv(model, o, crops, dataset, r.train.ms);
  if (!r.opencv.ran) log << "  not run: " << r.opencv.why_not << "\n";

  r.seconds = seconds_since(start);
  run.files = write_bench_report(r, o.out);
  return run;
}

}  // namespace binpick::bench
