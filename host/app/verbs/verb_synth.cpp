// `binpick synth`: synthetic bins as a BOP dataset (docs/synthesis.md, docs/formats.md). A model
// file gets the symmetries found on its mesh in models_info.json, a built-in part its stated ones;
// distractors likewise, as obj_ids 2, 3, ...
#include <CLI/CLI.hpp>
#include <array>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "host/app/options/dataset_options.hpp"
#include "host/app/options/model_options.hpp"
#include "host/app/verbs/verbs.hpp"
#include "host/app/options/scene_options.hpp"
#include "host/app/options/shard_options.hpp"
#include "host/shards/slurm_run.hpp"
#include "synth/synth_shards.hpp"
#include "host/core/output_lock.hpp"
#include "host/train/symmetry_describe.hpp"
#include "synth/part_mix.hpp"
#include "synth/synthesize.hpp"

namespace binpick::cli {
namespace {

struct SynthArgs {
  ModelArgs model;
  SynthOptions options;
  DatasetArgs dataset;
  std::vector<double> bin_size{600.0, 400.0, 300.0};
  std::vector<int> grid{7, 5};
  std::string cache_dir;
  SceneArgs scene;
  std::string bin_mesh;
  std::vector<double> intrinsics;
  ShardCliOptions shards;  // --shard K/N, --slurm
};

// --slurm: the bins as a job array of shards; the merge checks that every bin is there.
void synth_on_slurm(const SynthOptions& o, const SlurmOptions& slurm) {
  const ShardRecord record = synth_shard_record(o.out, o.bins, slurm.tasks);
  const ShardedBatch batch{synth_state_dir(o.out), record,
                           [&](int bin) { return bin_done(o.out, bin); },
                           [&] { return check_synth_shards(record); }};
  run_on_slurm(batch, slurm, task_command(own_command_line()), std::cout);
}

void run_synth(const SynthArgs& args) {
  SynthOptions o = args.options;
  const DatasetArgs& d = args.dataset;
  o.bins = d.bins;
  o.drop.objects = d.objects;
  o.seed = d.seed;
  o.width = d.width;
  o.height = d.height;
  o.drop.max_wall_seconds = d.max_wall_seconds;
  o.drop.bin_size_mm = Eigen::Vector3d(args.bin_size[0], args.bin_size[1], args.bin_size[2]);
  o.drop.grid_x = args.grid[0];
  o.drop.grid_y = args.grid[1];
  o.decompose.cache_dir = args.cache_dir;
  apply_scene_args(args.scene, o);
  o.bin_mesh = args.bin_mesh;
  if (!args.intrinsics.empty())
    o.intrinsics = std::array<double, 4>{args.intrinsics[0], args.intrinsics[1], args.intrinsics[2],
                                         args.intrinsics[3]};
  validate_synth_options(o);  // before loading: bad options fail fast
  o.shard = shard_of(args.shards);
  if (args.shards.slurm.enabled) return synth_on_slurm(o, args.shards.slurm);
  const auto load = [](const PartSpec& spec) {
    bool found = false;
    Model model = load_part_finding_symmetries(spec, &found);
    std::cout << fmt::format("{}: symmetry ({}): {}\n", spec.spec,
                             found ? "found on the mesh" : "stated for the built-in part",
                             describe_symmetries(model.symmetries));
    return model;
  };
  const Model model = load(part_spec_of(args.model));
  std::vector<Model> distractors;
  for (const DistractorSpec& d : o.distractors) distractors.push_back(load({d.model, {}}));
  // After the inputs load (a typo writes nothing); a shard shares it with the other shards.
  const OutputLock lock = OutputLock::directory(o.out, o.shard.index, o.shard.count);
  const SynthSummary s = synthesize(model, args.model.model, o, distractors);
  std::cout << fmt::format(
      "{}: {} bins made, {} already there; decomposition {:.1f} s, physics {:.1f} s, "
      "rendering {:.2f} s, writing {:.2f} s\n",
      o.out.string(), s.bins_made, s.bins_skipped, s.seconds_decompose, s.seconds_physics,
      s.seconds_render, s.seconds_write);
  if (s.bins_missing > 0)
    std::cout << fmt::format("shard {} done; {} bins of other shards still to make (`binpick "
                             "merge {}` checks the whole dataset)\n",
                             o.shard.name(), s.bins_missing, o.out.string());
  else if (o.shard.sharded())
    std::cout << check_synth_shards(synth_shard_record(o.out, o.bins, o.shard.count)) << "\n";
}

}  // namespace

void add_synth_verb(CLI::App& app) {
  auto args = std::make_shared<SynthArgs>();
  auto* verb = app.add_subcommand(
      "synth",
      "Make synthetic bins as a BOP dataset: drop parts into a bin with Bullet (convex pieces "
      "from HACD), render depth, intensity and the scene cloud with Vulkan. Rerunning the same "
      "command resumes; a larger --bins extends the dataset.");
  add_model_options(verb, args->model);
  SynthOptions& o = args->options;
  verb->add_option("--out", o.out, "dataset directory (created)")->required();
  add_dataset_options(verb, args->dataset, "number of bins (BOP scenes)");
  add_scene_options(verb, args->scene);
  verb->add_option("--noise", o.noise,
                   "Gaussian depth noise along the ray, sigma as a fraction of the part diameter "
                   "(the paper: 0 to 0.05)")
      ->capture_default_str();
  verb->add_option("--bin-size", args->bin_size, "bin interior W,D,H in mm")
      ->delimiter(',')
      ->expected(3)
      ->capture_default_str();
  verb->add_option("--grid", args->grid, "parts per wave as X,Y drop positions (paper: 7 x 5)")
      ->delimiter(',')
      ->expected(2)
      ->capture_default_str();
  verb->add_option("--drop-height", o.drop.drop_height_mm, "release height above the floor, mm")
      ->capture_default_str();
  verb->add_option("--camera-height", o.camera_height_mm,
                   "camera distance from the centre of the bin floor along the optical axis "
                   "(untilted: its height above the floor), mm")
      ->capture_default_str();
  verb->add_option("--intrinsics", args->intrinsics,
                   "camera intrinsics fx,fy,cx,cy in pixels (default: square pixels, principal "
                   "point at the image centre, the focal length that shows the whole bin "
                   "interior from the untilted camera)")
      ->delimiter(',')
      ->expected(4);
  verb->add_option("--bin-wall", o.drop.walls.wall_mm,
                   "built-in bin: wall and floor thickness, mm (the rim is as thick)")
      ->capture_default_str();
  verb->add_option("--bin-rim", o.drop.walls.rim_mm,
                   "built-in bin: width of the flat lip around the top of the walls, outward "
                   "from their outer faces, mm (0: none)")
      ->capture_default_str();
  verb->add_option("--bin-mesh", args->bin_mesh,
                   "the bin as a model file instead of the built-in one, for the physics (a "
                   "static triangle mesh) and the camera: world frame, mm, the interior floor's "
                   "centre at the origin, floor at z = 0, z up (--bin-size still places the drop "
                   "grid and the camera)");
  verb->add_option("--max-wave-seconds", o.drop.max_wave_seconds,
                   "simulated seconds a wave may take to come to rest before the next is released")
      ->capture_default_str();
  verb->add_flag("--final-settle", o.drop.final_settle_all_dynamic,
                 "after the last wave, keep the whole pile dynamic until all of it is at rest. "
                 "Parts at rest are frozen while later waves land, so they never feel all the "
                 "weight of the parts above them. By default the pile is made dynamic for one "
                 "simulated second at the end, then settles frozen again as in the waves: a "
                 "few parts of a finished bin would still shift by some mm if it were "
                 "released. This option removes most of those shifts at 2.2 to 2.4 times the "
                 "physics time");
  verb->add_flag("--masks", o.write_masks,
                 "also write mask/ (each part alone) and mask_visib/ (its visible pixels), one PNG per part");
  verb->add_flag("!--no-cloud", o.write_cloud, "do not write cloud/000000.ply");
  verb->add_option("--threads", o.threads,
                   "bins whose parts drop at once, each on its own core while earlier bins "
                   "render (Bullet steps one bin on one thread); 0: one per core. The dataset "
                   "is the same whatever the number")
      ->check(CLI::Range(0u, 1024u))
      ->capture_default_str();
  verb->add_option("--cache-dir", args->cache_dir,
                   "convex decomposition cache (default $BINPICK_CACHE_DIR or ~/.cache/binpick)");
  add_shard_options(verb, args->shards, "bins");
  verb->callback([args] { run_synth(*args); });
}

}  // namespace binpick::cli
