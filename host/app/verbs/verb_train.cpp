// `binpick train`: samples the part's surface, voxel-subsamples it, builds the point pair
// feature hash table on the OpenCL device, finds the part's symmetries and writes the .ppfm
// model file.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "host/app/options/model_options.hpp"
#include "host/app/options/train_options.hpp"
#include "host/app/output_file.hpp"
#include "host/app/verbs/verbs.hpp"
#include "host/core/output_lock.hpp"
#include "host/core/error.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/ppf_model_file.hpp"
#include "host/train/symmetry_describe.hpp"
#include "host/core/timing.hpp"
#include "host/formats/grasps/grasp_json.hpp"

namespace binpick::cli {
namespace {

// "none", or the look-alike poses and the probes that tell them apart (lookalike_holes.hpp).
std::string describe_look_alikes(const PpfModel& m) {
  if (m.lookalikes.empty()) return "none";
  std::vector<std::size_t> per(m.lookalikes.size(), 0);
  for (const std::uint32_t s : m.probe_lookalike) ++per[s];
  std::string text = fmt::format("{} (probes that tell them apart:", m.lookalikes.size());
  for (const std::size_t n : per) text += fmt::format(" {}", n);
  return text + ")";
}

struct TrainVerbArgs {
  ModelArgs model;
  std::string out;
  TrainArgs train;
  std::string grasps;  // a grasps JSON file, stored instead of the generated suction grasps
};

// "N suction, M parallel (from FILE | from the flat faces, cup D mm)".
std::string describe_grasps(const PpfModel& m, const std::string& file) {
  std::size_t suction = 0;
  for (const Grasp& g : m.grasps) suction += g.kind == Grasp::Kind::suction;
  const double cup = m.grasps.empty() ? 0 : m.grasps.front().size;
  return fmt::format("{} suction, {} parallel ({})", suction, m.grasps.size() - suction,
                     file.empty() ? fmt::format("from the faces, cup {:.1f} mm", cup)
                                  : "from " + file);
}

double ms(double s) { return s * 1e3; }

void run_train(const TrainVerbArgs& args) {
  const PpfTrainParams params = train_params_of(args.train);  // before the (slow) load: fail fast
  const std::vector<Grasp> given = args.grasps.empty() ? std::vector<Grasp>{}
                                                       : read_grasps_json(args.grasps);
  check_output_file(args.out);
  const OutputLock lock = OutputLock::file(args.out);
  const auto start = std::chrono::steady_clock::now();
  const Mesh mesh = load_part(part_spec_of(args.model)).mesh;
  const double load_s =
      seconds_since(start);
  // The OpenCL device starts on first use (its kernels built or read from PoCL's cache): timed
  // apart, so the stages below are the training's own.
  const auto device_start = std::chrono::steady_clock::now();
  ocl::Device& device = ocl::Device::shared();
  const double device_s = seconds_since(device_start);
  PpfTrainStats st;
  PpfModel model = train_ppf_model(mesh, params, &st, device);
  if (!given.empty()) model.grasps = given;
  const auto write_start = std::chrono::steady_clock::now();
  write_ppf_model(args.out, model);
  const auto end = std::chrono::steady_clock::now();
  const double write_s = std::chrono::duration<double>(end - write_start).count();
  const double total_s = std::chrono::duration<double>(end - start).count();

  const auto& t = st.table;
  std::cout << fmt::format(
      "model {}: diameter {:.3f} mm, voxel {:.3f} mm ({} of the diameter)\n"
      "  surface samples  {:>12}\n"
      "  model points     {:>12}\n"
      "  pairs            {:>12}   (ordered, points x (points - 1))\n"
      "  table entries    {:>12}\n"
      "  distinct keys    {:>12}   of {} ({} distance x {}^3 angle bins; alpha in {} bins)\n"
      "  symmetry: {}\n"
      "  look-alikes: {}\n"
      "  grasps: {}\n"
      "  edge probes: {}, {} of them continuing its faces (points just beyond the part's edges, "
      "for the edge test of thin parts)\n"
      "  time (ms): load {:.1f}, device {:.1f}, diameter {:.1f}, sampling {:.1f}, subsampling {:.1f}, "
      "table count {:.1f}, offsets {:.1f}, scatter {:.1f}, read back {:.1f}, symmetry {:.1f}, "
      "look-alikes {:.1f}, probes {:.1f}, grasps {:.1f}, write {:.1f}; total {:.1f}\n"
      "wrote {} ({:.2f} MB)\n",
      args.model.model, model.diameter, model.voxel_size, params.voxel_ratio, st.surface_samples,
      st.points, st.pairs, st.entries, st.distinct_keys, model.table.offsets.size() - 1,
      model.quant.n_dist, model.quant.n_angle, model.quant.n_alpha,
      describe_symmetries(model.symmetries), describe_look_alikes(model),
      describe_grasps(model, args.grasps),
      model.edge_probes.points.size(), model.edge_face_probes(), ms(load_s), ms(device_s), ms(st.diameter_s),
      ms(st.sample_s),
      ms(st.subsample_s), ms(t.count_s), ms(t.scan_s), ms(t.scatter_s), ms(t.read_s),
      ms(st.symmetry_s), ms(st.lookalike_s), ms(st.probe_s), ms(st.grasp_s), ms(write_s), ms(total_s), args.out,
      double(std::filesystem::file_size(args.out)) / 1e6);
}

}  // namespace

void add_train_verb(CLI::App& app) {
  auto args = std::make_shared<TrainVerbArgs>();
  auto* verb = app.add_subcommand(
      "train",
      "Build the point pair feature model of a part: sample its surface uniformly, voxel "
      "subsample, hash all point pair features on the OpenCL device, find the part's "
      "rotational symmetries and the suction grasps its flat faces offer, write a .ppfm file");
  add_model_options(verb, args->model);
  verb->add_option("--out", args->out, "model file to write (.ppfm)")->required();
  add_train_options(verb, args->train, "model");
  verb->add_option("--grasps", args->grasps,
                   "grasps JSON file (suction and parallel-jaw grasps in the model frame, "
                   "docs/picks.md) stored in the model instead of the suction grasps "
                   "generated from its flat faces");
  verb->callback([args] { run_train(*args); });
}

}  // namespace binpick::cli
