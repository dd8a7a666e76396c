// The Bullet world of one bin: gravity, the static bin (synth/bin/bin_model.hpp: the boxes of
// the built-in bin, or a triangle mesh), a ground under it that catches parts thrown out, and
// the part bodies (one or several kinds) with their rest tracking. Owns everything Bullet needs
// and tears it down in order.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "synth/physics/drop.hpp"
#include "synth/physics/part_shape.hpp"
#include "synth/physics/rest_tracker.hpp"
#include "synth/physics/separated_pair_skip.hpp"

namespace binpick {

class BinWorld {
 public:
  // The ground under the bin is this thick (units): a part below it tunnelled through.
  static constexpr btScalar kGroundThickness = 20;

  BinWorld(const DropOptions& options, const PartShape& part);
  // kinds: the shapes of the kinds of part (outlive the world), at least one.
  BinWorld(const DropOptions& options, std::vector<const PartShape*> kinds);
  ~BinWorld();
  BinWorld(const BinWorld&) = delete;
  BinWorld& operator=(const BinWorld&) = delete;

  // A dynamic part of `kind` released at rest at `body_pose` (principal frame -> world, units).
  btRigidBody* add_part(const btTransform& body_pose, int kind = 0);
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
  // Whether the shapes of two parts come closer than `within` (units). Bullet keeps no
  // contacts between two static (frozen) parts, so this runs the collision test itself.
  bool touching(btRigidBody& a, btRigidBody& b, btScalar within);
  // Takes a part out of the simulation (one that fell off the world); it stays in parts()
  // with isInWorld() false.
  void remove(btRigidBody* body);

  // Every part added, in order.
  const std::vector<btRigidBody*>& parts() const { return parts_; }
  int kind(const btRigidBody& body) const {
    return kinds_of_parts_[std::size_t(body.getUserIndex())];
  }
  btDispatcher& dispatcher() { return dispatcher_; }
  // Null when DropOptions::skip_apart_hulls is off.
  const SeparatedPairSkip* apart_pair_skip() const { return skip_apart_.get(); }
  const PartShape& shape(int kind) const { return *kinds_[std::size_t(kind)]; }
  // Some kind has a hull thinner than DropOptions::sheet_hull_mm: the pile is of sheet parts.
  bool sheet_pile() const { return thinnest_mm_ < options_.sheet_hull_mm; }
  // A part whose centre of mass is below this (units) fell through the ground.
  btScalar lost_below() const { return lost_below_; }

 private:
  void add_static(btCollisionShape* shape, const btVector3& centre);
  void add_static_box(const btVector3& half_extents, const btVector3& centre);
  void add_static_mesh(const Mesh& mesh);
  double next_step_length() const;

  const DropOptions options_;
  const std::vector<const PartShape*> kinds_;
  double thinnest_mm_ = 0;
  double contact_erp_ = 0;  // Bullet's error reduction of contacts at the full step (step())
  btScalar lost_below_ = 0;
  const btScalar rolling_friction_;  // per body, also spinning friction
  btDefaultCollisionConfiguration collision_configuration_;
  btCollisionDispatcher dispatcher_{&collision_configuration_};
  std::unique_ptr<SeparatedPairSkip> skip_apart_;  // before world_: outlives its pairs
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &collision_configuration_};
  std::vector<std::unique_ptr<btCollisionShape>> static_shapes_;
  std::vector<float> mesh_vertices_;   // units; the triangle mesh shape reads them in place
  std::vector<int> mesh_indices_;
  std::unique_ptr<btTriangleIndexVertexArray> mesh_arrays_;
  std::vector<std::unique_ptr<btRigidBody>> static_bodies_;
  std::vector<std::unique_ptr<btRigidBody>> part_bodies_;
  std::vector<btRigidBody*> parts_;
  std::vector<int> kinds_of_parts_;  // by user index
  RestTracker rest_;  // indexed by a part body's user index = its index in parts_ (bin: -1)
};

}  // namespace binpick
