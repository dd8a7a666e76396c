#include "synth/physics/pile_freezer.hpp"

#include <LinearMath/btAabbUtil2.h>

#include <unordered_set>
#include <vector>

namespace binpick {
namespace {

// A contact closer than this (units) counts as touching; Bullet keeps manifold points a
// little beyond contact, and a part 0.2 mm away from a moving one is not being pushed.
constexpr btScalar kTouching = btScalar(0.02);
// A part pushes its frozen neighbours awake when it moves this many times faster than the
// rest speeds: a landing or tumbling part, not one drifting slowly into place (which would
// keep thawing and refreezing its neighbours for nothing).
constexpr double kPushingSpeedRatio = 3.0;

bool touching(const btPersistentManifold& manifold) {
  for (int c = 0; c < manifold.getNumContacts(); ++c)
    if (manifold.getContactPoint(c).getDistance() < kTouching) return true;
  return false;
}

}  // namespace

FreezeCounts update_frozen_parts(BinWorld& world) {
  // Frozen parts hit by a pushing part wake up; parts touching one not yet at rest stay
  // dynamic, so that they take its weight and settle with it before they freeze.
  std::unordered_set<const btCollisionObject*> hit, unsettled;
  btDispatcher& dispatcher = world.dispatcher();
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold& manifold = *dispatcher.getManifoldByIndexInternal(m);
    if (!touching(manifold)) continue;
    const auto* a = btRigidBody::upcast(manifold.getBody0());
    const auto* b = btRigidBody::upcast(manifold.getBody1());
    if (world.speed_ratio(*a) >= kPushingSpeedRatio && world.frozen(*b)) hit.insert(b);
    if (world.speed_ratio(*b) >= kPushingSpeedRatio && world.frozen(*a)) hit.insert(a);
    if (!world.at_rest(*a)) unsettled.insert(b);
    if (!world.at_rest(*b)) unsettled.insert(a);
  }
  // The parts hit, and the frozen parts touching them. Boxes first: the collision test is the
  // costly part.
  std::vector<btRigidBody*> hit_parts;
  for (btRigidBody* body : world.parts())
    if (hit.count(body) > 0 && body->isInWorld()) hit_parts.push_back(body);
  std::unordered_set<const btCollisionObject*> wake(hit.begin(), hit.end());
  const btVector3 near(kTouching, kTouching, kTouching);
  for (btRigidBody* body : world.parts()) {
    if (!body->isInWorld() || !world.frozen(*body) || wake.count(body) > 0) continue;
    btVector3 lo, hi;
    body->getAabb(lo, hi);
    for (btRigidBody* hit_part : hit_parts) {
      btVector3 hit_lo, hit_hi;
      hit_part->getAabb(hit_lo, hit_hi);
      if (TestAabbAgainstAabb2(lo - near, hi + near, hit_lo, hit_hi) &&
          world.touching(*hit_part, *body, kTouching)) {
        wake.insert(body);
        break;
      }
    }
  }

  FreezeCounts counts;
  for (btRigidBody* body : world.parts()) {
    if (!body->isInWorld()) continue;
    if (world.frozen(*body)) {
      if (wake.count(body) > 0) {
        world.thaw(body);
        ++counts.thawed;
      }
    } else if (world.at_rest(*body) && unsettled.count(body) == 0) {
      world.freeze(body);
      ++counts.frozen;
    }
  }
  return counts;
}

}  // namespace binpick
