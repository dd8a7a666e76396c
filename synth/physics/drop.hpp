// Drops parts into a bin with Bullet until they are at rest: the ground truth of a synthetic
// bin (paper III-A and IV). World frame: origin at the centre of the bin floor, z up, the
// interior spans x in [-w/2, w/2], y in [-d/2, d/2], z in [0, h]. All results in mm.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "host/core/mesh.hpp"
#include "synth/bin/bin_model.hpp"
#include "synth/decompose/convex_parts.hpp"

namespace binpick {

// Defaults are the paper's scene (docs/parameters.md) and settings measured to settle a 350-part bin
// quickly (bench/programs/bench_synth_physics.cpp).
struct DropOptions {
  Eigen::Vector3d bin_size_mm{600.0, 400.0, 300.0};  // interior: x width, y depth, z wall height
  // The bin the parts collide with (synth/bin/bin_model.hpp): `bin` if set (a mesh bin), else
  // the built-in bin with these walls around bin_size_mm. The interior (bin_size_mm) places
  // the drop positions and decides which parts ended in the bin either way.
  BuiltInBinWalls walls;
  std::shared_ptr<const BinModel> bin;
  int objects = 350;
  int grid_x = 7;                 // drop positions along x per wave
  int grid_y = 5;                 // along y; a wave is grid_x * grid_y parts, the last partial
  double drop_height_mm = 600.0;  // of the parts' centres of mass above the floor
  std::uint64_t seed = 1;         // orientations; same seed, same bin, bit for bit
  // A part is at rest once how far it moved and turned over a quarter second, over that time
  // (which cancels contact jitter, rest_tracker.hpp), stayed under both speeds for
  // rest_seconds; a wave is done when all parts are. 0.1 rad/s turns the rim of the paper's
  // part at 2.6 mm/s, half the linear speed. At 0.05 tori turning in place in the pile, their
  // centres still, kept waves going for seconds: the 350-part torus bin took 1.4 times as long
  // (bench).
  double rest_linear_speed_mm_s = 5.0;
  double rest_angular_speed_rad_s = 0.1;
  double rest_seconds = 0.25;
  double max_wave_seconds = 60.0;  // simulated; an unsettled wave is reported, the next released
  double max_wall_seconds = 0.0;   // whole bin, wall clock, 0 = unlimited; stops the drop
  // Simulation: the step (deterministic: it depends only on the state), contact solver,
  // materials. While a part moves faster than step_travel times the thinnest hull width per
  // time_step_s, the step shrinks so it cannot pass through another part unseen.
  double time_step_s = 1.0 / 120.0;
  double step_travel = 0.5;
  int solver_iterations = 10;
  double friction = 0.5;
  double restitution = 0.1;
  // Resistance to rolling and spinning in place, as the lever arm of the contact force (mm):
  // real contacts have a patch, Bullet's are points, and without it a torus on its rim or a
  // part pivoting on a corner can roll or spin for a minute. 0.5 mm, a patch of about a
  // millimetre: at 0.1 the 350-part torus bin took 10 to 25 % longer to come to rest.
  double rolling_friction_mm = 0.5;
  // Parts at rest among parts at rest become static until a falling part hits them or a part
  // touching them: a landing wave then wakes only what it pushes, not the whole pile
  // (pile_freezer.hpp).
  // About ten times faster. The price: a frozen part does not feel the weight of parts that
  // land on it later, and one frozen while slowly tipping stays tipped. Released all at once
  // for a second after the last wave (no final settling), a 350-part bin still moves: 50 to
  // 160 parts by over 1 mm, up to 9 by over 5 mm, the worst (toppling) by up to 28 mm (the
  // benchmark's L-bracket and torus, seeds 1 to 3; the numbers below likewise).
  bool freeze_resting = true;
  // With freeze_resting, the final settling: after the last wave every part is made dynamic,
  // the whole pile moves under all its weight for this long (simulated s), then settles with
  // freezing as in the waves. The default second topples what was frozen tipping and lets
  // the pile sag: then 20 to 110 parts move over 1 mm, 0 to 5 over 5 mm, the worst 3 to 9 mm,
  // for 5 to 15 % more time. 0: none.
  double final_all_dynamic_seconds = 1.0;
  // Instead, keep every part dynamic until the whole pile is at rest: then 5 to 30 parts move
  // over 1 mm, 0 to 2 over 5 mm, but a bin takes 2.2 to 2.4 times as long (the pile jitters as
  // a whole, so it comes to rest late). Off by default: the second above removes the large
  // shifts at a fraction of the cost, and what it leaves is under the rest speed.
  bool final_settle_all_dynamic = false;
  // Sheet parts (some hull of some kind thinner than sheet_hull_mm): no release at the end
  // (final_all_dynamic_seconds; final_settle_all_dynamic still applies) and
  // sheet_solver_iterations contact iterations throughout. Released all at once, a pile of
  // eight layers of 1.5 mm plates sagged until plates passed through each other: in a
  // 350-plate bin 292 plates crossed another (mid-planes under 1 mm apart over a fifth of a
  // plate or more) with the release, 61 without it at 10 iterations, none without it at 50
  // (in about the same time: 35 s instead of 38); with the release, 50 iterations left 136.
  // Thicker hulls (the cap screw's 2.9 mm, the bracket's 3.1, the tee's 3.6) keep the release:
  // the bracket's and the tee's 350-part bins overlap under 1 mm (docs/synthesis.md).
  double sheet_hull_mm = 2.5;
  int sheet_solver_iterations = 50;
  // Pairs of hulls that are clearly apart skip Bullet's contact test (separated_pair_skip.hpp):
  // the same bin, bit for bit, in 6 to 27 % less time (the built-in parts). Off only to check
  // that.
  bool skip_apart_hulls = true;
};

struct DropProgress {
  int wave = 0;  // 0-based, of `waves`
  int waves = 0;
  int parts_dropped = 0;           // including this wave
  int parts_moving = 0;            // not yet at rest
  double simulated_seconds = 0.0;  // since the first wave
};
using ProgressFn = std::function<void(const DropProgress&)>;

struct DropStats {
  int waves = 0;
  double simulated_seconds = 0.0;
  std::vector<double> wave_simulated_seconds;  // per wave, then the final settling's phases
  std::vector<double> wave_wall_seconds;
  bool settled = false;    // every wave (and the final settling) came to rest in the limits
  int parts_left_bin = 0;  // ended outside the interior; not in `poses`
  int parts_frozen = 0;    // times a part was made static (see DropOptions::freeze_resting)
  int parts_thawed = 0;    // times a frozen part was hit and made dynamic again
  bool full = false;       // the pile reached over the walls: the waves after it were not released
  bool sheet_pile = false;  // a hull under DropOptions::sheet_hull_mm: no release, more iterations
  std::vector<int> unsettled;  // indices into DropResult::poses of parts moving when a limit stopped it
  std::string message;     // what went wrong when !settled, full or parts_left_bin > 0
};

struct DropResult {
  std::vector<Eigen::Isometry3d> poses;  // part frame -> world, mm; one per part in the bin
  std::vector<int> kinds;                // per pose: which of the dropped kinds it is
  DropStats stats;
};

// One kind of part in a mixed drop: its hulls collide, its closed mesh (mm) gives mass, centre
// of mass and inertia.
struct DropKind {
  const ConvexParts* hulls = nullptr;
  const Mesh* mesh = nullptr;
};

// The bin the options describe (DropOptions::bin, or the built-in bin). Throws InputError for
// bad walls.
std::shared_ptr<const BinModel> bin_of(const DropOptions& options);

// Throws InputError for a bin, count, grid, height, speed or time that is not positive and
// finite, or a part too large for the grid of drop positions.
void validate_drop_options(const DropOptions& options);

// `hulls` collide; `part` (closed, mm) gives mass, centre of mass and inertia. Single threaded
// and deterministic unless max_wall_seconds cuts it short. Bins may drop in parallel threads
// (drops_ahead.hpp) only with the same rest_seconds (Bullet's deactivation time is a
// process-wide global).
DropResult drop_parts(const ConvexParts& hulls, const Mesh& part, const DropOptions& options,
                      const ProgressFn& progress = {});

// Several kinds of part in one pile: the k-th part released is kinds[sequence[k]], with
// sequence.size() == options.objects. Waves are spaced for the largest kind. With one kind and
// sequence all 0, the same bin as drop_parts, bit for bit.
DropResult drop_parts(const std::vector<DropKind>& kinds, const std::vector<int>& sequence,
                      const DropOptions& options, const ProgressFn& progress = {});

}  // namespace binpick
