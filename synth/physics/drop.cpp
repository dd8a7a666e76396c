// The wave loop: release a grid of randomly oriented parts, step until every part is at rest,
// repeat; let the whole pile settle once more with nothing frozen, for a second or until it
// is at rest; report part poses in mm.
#include "synth/physics/drop.hpp"

#include <algorithm>
#include <chrono>
#include <random>
#include <string>

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/core/timing.hpp"
#include "synth/physics/bin_world.hpp"
#include "synth/physics/bullet_units.hpp"
#include "synth/physics/drop_layout.hpp"
#include "synth/physics/drop_random.hpp"
#include "synth/physics/mass_properties.hpp"
#include "synth/physics/part_shape.hpp"
#include "synth/physics/pile_freezer.hpp"

namespace binpick {
namespace {

// Checking every few steps is enough to see a wave come to rest, and costs little.
constexpr int kStepsPerCheck = 6;
constexpr int kChecksPerProgress = 5;

using Clock = std::chrono::steady_clock;

void append_message(std::string& message, const std::string& text) {
  if (!message.empty()) message += "; ";
  message += text;
}

// "3, 17, 22", the first 20 and a count of the rest: a message stays one line.
std::string index_list(const std::vector<int>& indices) {
  std::string text;
  for (std::size_t i = 0; i < indices.size() && i < 20; ++i)
    text += (i ? ", " : "") + std::to_string(indices[i]);
  if (indices.size() > 20) text += " and " + std::to_string(indices.size() - 20) + " more";
  return text;
}

// The highest point of any part in the world (units), the floor if none; with `interior`, of
// the parts whose centre lies over the bin's interior (not on the rim or outside).
btScalar pile_top(const BinWorld& world, const Eigen::Vector3d* interior_mm = nullptr) {
  btScalar top = 0;
  for (const btRigidBody* body : world.parts()) {
    if (!body->isInWorld()) continue;
    const btVector3 c = body->getCenterOfMassPosition() * btScalar(kMmPerUnit);
    if (interior_mm && (std::abs(c.x()) > 0.5 * interior_mm->x() ||
                        std::abs(c.y()) > 0.5 * interior_mm->y()))
      continue;
    btVector3 lo, hi;
    body->getAabb(lo, hi);
    top = std::max(top, hi.z());
  }
  return top;
}

// Ended in the bin: its centre over the interior, and not fallen through the floor: some of it
// (its box) above the floor. Not its centre above the floor: a 1.5 mm sheet lying on the floor
// under a released pile sinks a millimetre into it, and 20 of 350 plates were left out.
bool inside_bin(const btRigidBody& body, const Eigen::Vector3d& bin_mm) {
  const Eigen::Vector3d centre_mm = to_mm(body.getCenterOfMassPosition());
  btVector3 lo, hi;
  body.getAabb(lo, hi);
  return std::abs(centre_mm.x()) <= 0.5 * bin_mm.x() &&
         std::abs(centre_mm.y()) <= 0.5 * bin_mm.y() && hi.z() > 0;
}

// Runs one bin: the waves, the final settling, the limits, the statistics and the progress.
class BinDrop {
 public:
  BinDrop(BinWorld& world, const DropOptions& options, const ProgressFn& progress, DropStats& stats)
      : world_(world), options_(options), progress_(progress), stats_(stats) {}

  bool out_of_wall_time() const { return out_of_wall_time_; }

  // Steps until every part is at rest or a limit is hit, or for `phase_seconds` (simulated)
  // if that is positive; `label` names the phase in messages.
  void settle(int wave, bool freeze, const std::string& label, double phase_seconds = 0.0) {
    const auto wave_start = Clock::now();
    double seconds = 0.0;
    for (int check = 0;; ++check) {
      for (int s = 0; s < kStepsPerCheck; ++s) seconds += world_.step();
      if (freeze) {
        const FreezeCounts counts = update_frozen_parts(world_);
        stats_.parts_frozen += counts.frozen;
        stats_.parts_thawed += counts.thawed;
      }
      const int moving = count_moving();
      if (progress_ && (moving == 0 || check % kChecksPerProgress == 0))
        progress_({wave, stats_.waves, static_cast<int>(world_.parts().size()), moving,
                   stats_.simulated_seconds + seconds});
      if (moving == 0 || (phase_seconds > 0.0 && seconds >= phase_seconds)) break;
      if (seconds >= options_.max_wave_seconds) {
        stats_.settled = false;
        append_message(stats_.message,
                       label + " still had " + std::to_string(moving) + " parts moving after " +
                           fmt::format("{:g}", options_.max_wave_seconds) + " simulated s");
        break;
      }
      if (options_.max_wall_seconds > 0.0 && seconds_since(start_) > options_.max_wall_seconds) {
        stats_.settled = false;
        out_of_wall_time_ = true;
        append_message(stats_.message, "stopped in " + label + " after " +
                                           fmt::format("{:g}", options_.max_wall_seconds) +
                                           " wall s, with parts moving");
        break;
      }
    }
    stats_.simulated_seconds += seconds;
    stats_.wave_simulated_seconds.push_back(seconds);
    stats_.wave_wall_seconds.push_back(seconds_since(wave_start));
  }

 private:
  int count_moving() {
    int moving = 0;
    for (btRigidBody* body : world_.parts()) {
      if (!body->isInWorld()) continue;
      if (body->getCenterOfMassPosition().z() < world_.lost_below())
        world_.remove(body);  // tunnelled through the floor: it would fall forever
      else if (!world_.at_rest(*body))
        ++moving;
    }
    return moving;
  }

  BinWorld& world_;
  const DropOptions& options_;
  const ProgressFn& progress_;
  DropStats& stats_;
  const Clock::time_point start_ = Clock::now();
  bool out_of_wall_time_ = false;
};

}  // namespace

std::shared_ptr<const BinModel> bin_of(const DropOptions& options) {
  if (options.bin) return options.bin;
  return std::make_shared<const BinModel>(built_in_bin(options.bin_size_mm, options.walls));
}

DropResult drop_parts(const ConvexParts& hulls, const Mesh& part, const DropOptions& options,
                      const ProgressFn& progress) {
  const std::vector<int> one_kind(std::size_t(std::max(options.objects, 0)), 0);
  return drop_parts({DropKind{&hulls, &part}}, one_kind, options, progress);
}

DropResult drop_parts(const std::vector<DropKind>& kinds, const std::vector<int>& sequence,
                      const DropOptions& options, const ProgressFn& progress) {
  validate_drop_options(options);
  if (kinds.empty()) throw InputError("no kind of part to drop");
  if (sequence.size() != std::size_t(options.objects))
    throw InputError("the drop sequence names " + std::to_string(sequence.size()) + " parts for " +
                     std::to_string(options.objects) + " objects");
  for (const int k : sequence)
    if (k < 0 || std::size_t(k) >= kinds.size())
      throw InputError("the drop sequence names an unknown kind");
  std::vector<std::unique_ptr<PartShape>> shapes;
  std::vector<const PartShape*> shape_list;
  double radius_mm = 0.0;
  for (const DropKind& k : kinds) {
    if (!k.hulls || !k.mesh) throw InputError("a kind of part without hulls or mesh");
    shapes.push_back(std::make_unique<PartShape>(*k.hulls, mass_properties(*k.mesh)));
    shape_list.push_back(shapes.back().get());
    radius_mm = std::max(radius_mm, shapes.back()->bounding_radius_mm());
  }
  BinWorld world(options, shape_list);
  std::mt19937_64 rng(options.seed);

  DropResult result;
  DropStats& stats = result.stats;
  const int per_wave = options.grid_x * options.grid_y;
  stats.waves = (options.objects + per_wave - 1) / per_wave;
  stats.settled = true;
  BinDrop drop(world, options, progress, stats);

  for (int wave = 0; wave < stats.waves && !drop.out_of_wall_time(); ++wave) {
    // A pile up to the top of the walls has no room for another wave: its parts would land
    // on the heap and slide out over the walls, wave after wave, for as long as asked.
    const double top_mm = pile_top(world, &options.bin_size_mm) * kMmPerUnit;
    if (top_mm > options.bin_size_mm.z()) {
      stats.full = true;
      append_message(stats.message,
                     "the bin was full after " + std::to_string(world.parts().size()) + " of " +
                         std::to_string(options.objects) + " parts (the pile reached " +
                         std::to_string(int(top_mm)) + " mm, the walls " +
                         std::to_string(int(options.bin_size_mm.z())) +
                         " mm): no further wave released");
      break;
    }
    const int count = std::min(per_wave, options.objects - wave * per_wave);
    const double lowest_centre_mm = pile_top(world) * kMmPerUnit + 1.1 * radius_mm;
    for (const auto& at : wave_drop_positions(options, count, radius_mm, lowest_centre_mm)) {
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = uniform_rotation(rng).toRotationMatrix();
      pose.translation() = at;
      world.add_part(to_units(pose), sequence[world.parts().size()]);
    }
    drop.settle(wave, options.freeze_resting, "wave " + std::to_string(wave + 1));
  }
  // Sheet parts are not released all at once (DropOptions::sheet_hull_mm says why).
  stats.sheet_pile = world.sheet_pile();
  const double all_dynamic_seconds =
      options.final_settle_all_dynamic || stats.sheet_pile ? 0.0
                                                           : options.final_all_dynamic_seconds;
  if (options.freeze_resting && !drop.out_of_wall_time() &&
      (options.final_settle_all_dynamic || all_dynamic_seconds > 0.0)) {
    for (btRigidBody* body : world.parts())
      if (body->isInWorld() && world.frozen(*body)) world.thaw(body);
    drop.settle(stats.waves - 1, false, "the final settling", all_dynamic_seconds);
    if (!options.final_settle_all_dynamic && !drop.out_of_wall_time())
      drop.settle(stats.waves - 1, true, "the final settling");
  }

  for (const btRigidBody* body : world.parts()) {
    const Eigen::Isometry3d body_pose = to_mm(body->getWorldTransform());
    if (!body->isInWorld() || !inside_bin(*body, options.bin_size_mm)) {
      ++stats.parts_left_bin;
      continue;
    }
    const int kind = world.kind(*body);
    if (!world.at_rest(*body)) stats.unsettled.push_back(int(result.poses.size()));
    result.poses.push_back(body_pose * shapes[std::size_t(kind)]->body_in_part().inverse());
    result.kinds.push_back(kind);
  }
  if (!stats.unsettled.empty())
    append_message(stats.message, "parts not at rest (scene_gt indices): " +
                                      index_list(stats.unsettled));
  if (stats.parts_left_bin > 0)
    append_message(stats.message, std::to_string(stats.parts_left_bin) +
                                      " parts ended outside the bin and were left out");
  return result;
}

}  // namespace binpick
