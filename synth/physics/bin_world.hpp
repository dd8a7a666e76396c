// The Bullet world of one bin: gravity, a static floor and four thick walls, and the part
// bodies with their rest tracking. Owns everything Bullet needs and tears it down in order.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "synth/physics/drop.hpp"
#include "synth/physics/part_shape.hpp"
#include "synth/physics/rest_tracker.hpp"

namespace binpick {

class BinWorld {
 public:
  // Walls and floor this thick (units) stop any part that moves less than this per step.
  static constexpr btScalar kWallThickness = 20;

  BinWorld(const DropOptions& options, const PartShape& part);
  ~BinWorld();
  BinWorld(const BinWorld&) = delete;
  BinWorld& operator=(const BinWorld&) = delete;

  // A dynamic part released at rest at `body_pose` (principal frame -> world, units).
  btRigidBody* add_part(const btTransform& body_pose);
  // Advances the simulation by one step and returns its length (s): time_step_s, shorter
  // while a part moves fast enough to pass through another (see DropOptions::step_travel).
  double step();

  // Frozen, static (the bin), asleep, or calm for rest_seconds (see RestTracker).
  bool at_rest(const btRigidBody& body) const;
  // Averaged speed over the rest speed (RestTracker::speed_ratio); 0 for static bodies.
  double speed_ratio(const btRigidBody& body) const;
  bool frozen(const btRigidBody& body) const { return body.isStaticObject(); }
  // Makes a part static: it still supports the pile but no longer joins Bullet's islands,
  // so a part landing on the pile wakes only what it touches.
  void freeze(btRigidBody* body);
  // Makes a frozen part dynamic again, at rest where it was.
  void thaw(btRigidBody* body);
  // Takes a part out of the simulation (one that fell off the world); it stays in parts()
  // with isInWorld() false.
  void remove(btRigidBody* body);

  // Every part added, in order.
  const std::vector<btRigidBody*>& parts() const { return parts_; }
  btDispatcher& dispatcher() { return dispatcher_; }
  const PartShape& part() const { return part_; }

 private:
  void add_static_box(const btVector3& half_extents, const btVector3& centre);
  double next_step_length() const;

  const DropOptions options_;
  const PartShape& part_;
  const btScalar rolling_friction_;  // per body, also spinning friction
  btDefaultCollisionConfiguration collision_configuration_;
  btCollisionDispatcher dispatcher_{&collision_configuration_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &collision_configuration_};
  std::vector<std::unique_ptr<btBoxShape>> box_shapes_;
  std::vector<std::unique_ptr<btRigidBody>> static_bodies_;
  std::vector<std::unique_ptr<btRigidBody>> part_bodies_;
  std::vector<btRigidBody*> parts_;
  RestTracker rest_;  // indexed by a part body's user index = its index in parts_ (bin: -1)
};

}  // namespace binpick
