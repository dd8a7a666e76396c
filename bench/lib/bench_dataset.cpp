#include "bench/lib/bench_dataset.hpp"

#include <map>

#include <nlohmann/json.hpp>

#include "host/core/atomic_file.hpp"
#include "host/core/read_file.hpp"
#include "synth/pile_cache.hpp"
#include "synth/synthesize.hpp"

namespace binpick::bench {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::path times_path(const BenchOptions& o, bool real) {
  return o.out / (real ? "synth_times_real.json" : "synth_times.json");
}

// The real cell's sensor: structured light, farther and tilted (as bench/realistic_sets.sh's
// basket sets are seen).
void real_view(SynthOptions& s, const BenchOptions& o) {
  s.width = o.real_width;
  s.height = o.real_height;
  s.sensor.kind = SensorModel::Kind::structured_light;
  s.camera_height_mm = o.real_camera_height_mm;
  s.camera_tilt_deg = o.real_camera_tilt_deg;
}

// Times of earlier runs by bin; a missing or unreadable record only means they are unknown.
std::map<int, SynthBin> read_times(const fs::path& path) {
  std::map<int, SynthBin> times;
  if (!fs::exists(path)) return times;
  try {
    const json record = json::parse(read_file_bytes(path));  // named: the loop refers into it
    for (const auto& j : record.at("bins")) {
      SynthBin b;
      b.bin = j.at("bin");
      b.physics_s = j.at("physics_s");
      b.render_s = j.at("render_s");
      b.decompose_s = j.at("decompose_s");
      b.write_s = j.at("write_s");
      b.measured_now = false;
      times[b.bin] = b;
    }
  } catch (const std::exception&) {
    times.clear();
  }
  return times;
}

void write_times(const fs::path& path, const std::vector<SynthBin>& bins) {
  json j = {{"bins", json::array()}};
  for (const auto& b : bins)
    j["bins"].push_back({{"bin", b.bin}, {"physics_s", b.physics_s}, {"render_s", b.render_s},
                         {"decompose_s", b.decompose_s}, {"write_s", b.write_s}});
  write_file_atomically(path, [&](std::ostream& os) { os << j.dump(2) << "\n"; });
}

}  // namespace

fs::path dataset_dir(const BenchOptions& o) { return o.out / "dataset"; }
fs::path real_dataset_dir(const BenchOptions& o) { return o.out / "dataset_real"; }

std::vector<SynthBin> make_bench_dataset(const Model& part, const BenchOptions& o, bool real,
                                         PileCache* piles) {
  SynthOptions s;
  s.out = real ? real_dataset_dir(o) : dataset_dir(o);
  s.seed = o.seed;
  s.width = o.width;
  s.height = o.height;
  if (real) real_view(s, o);
  s.write_cloud = false;  // detection reads the depth image
  s.drop.objects = o.objects;
  validate_synth_options(s);
  fs::create_directories(o.out);
  std::map<int, SynthBin> known = read_times(times_path(o, real));
  std::vector<SynthBin> bins;
  // One bin per call: synthesize resumes, so call k makes bin k alone and its summary is that
  // bin's time.
  for (int k = 0; k < o.bins; ++k) {
    s.bins = k + 1;
    const SynthSummary sum = synthesize(part, describe(o.part), s, {}, piles);
    SynthBin b;
    b.bin = k;
    if (sum.bins_made > 0) {
      b.physics_s = sum.seconds_physics;
      b.render_s = sum.seconds_render;
      b.decompose_s = sum.seconds_decompose;
      b.write_s = sum.seconds_write;
    } else if (known.count(k)) {
      b = known[k];
    } else {
      b.measured_now = false;  // made by an earlier run that kept no record: time unknown
      b.physics_s = b.render_s = b.decompose_s = b.write_s = -1;
    }
    bins.push_back(b);
  }
  write_times(times_path(o, real), bins);
  return bins;
}

}  // namespace binpick::bench
