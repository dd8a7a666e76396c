#include "synth/physics/bin_world.hpp"

#include <algorithm>
#include <cmath>

#include "synth/physics/bullet_units.hpp"

namespace binpick {
namespace {

// The adaptive step never goes below time_step_s / this: bounds the cost of a part that is
// thin, fast or both.
constexpr double kMaxStepDivision = 20.0;

}  // namespace

BinWorld::BinWorld(const DropOptions& options, const PartShape& part)
    : options_(options),
      part_(part),
      // Bullet multiplies the two bodies' coefficients of a contact.
      rolling_friction_(btScalar(std::sqrt(options.rolling_friction_mm / kMmPerUnit))),
      rest_(options.rest_linear_speed_mm_s / kMmPerUnit, options.rest_angular_speed_rad_s,
            options.rest_seconds) {
  world_.setGravity(btVector3(0, 0, btScalar(-kGravityUnits)));
  world_.getSolverInfo().m_numIterations = options.solver_iterations;
  // Bullet puts an island to sleep once all its bodies have been below their sleeping
  // thresholds this long; the same duration as our own rest test. (A process-wide global.)
  gDeactivationTime = btScalar(options.rest_seconds);

  const btVector3 half = to_units(options.bin_size_mm) * btScalar(0.5);
  const btScalar t = kWallThickness;
  // The floor reaches well past the walls, so a part thrown out lands and comes to rest
  // (and is reported) instead of falling forever.
  add_static_box(btVector3(3 * half.x() + t, 3 * half.y() + t, t / 2), btVector3(0, 0, -t / 2));
  for (const btScalar side : {btScalar(-1), btScalar(1)}) {
    add_static_box(btVector3(t / 2, half.y() + t, half.z()),
                   btVector3(side * (half.x() + t / 2), 0, half.z()));
    add_static_box(btVector3(half.x() + t, t / 2, half.z()),
                   btVector3(0, side * (half.y() + t / 2), half.z()));
  }
}

BinWorld::~BinWorld() {
  for (auto& body : part_bodies_)
    if (body->isInWorld()) world_.removeRigidBody(body.get());
  for (auto& body : static_bodies_) world_.removeRigidBody(body.get());
}

void BinWorld::add_static_box(const btVector3& half_extents, const btVector3& centre) {
  box_shapes_.push_back(std::make_unique<btBoxShape>(half_extents));
  btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, box_shapes_.back().get());
  info.m_startWorldTransform.setIdentity();
  info.m_startWorldTransform.setOrigin(centre);
  info.m_friction = btScalar(options_.friction);
  info.m_restitution = btScalar(options_.restitution);
  info.m_rollingFriction = info.m_spinningFriction = rolling_friction_;
  static_bodies_.push_back(std::make_unique<btRigidBody>(info));
  world_.addRigidBody(static_bodies_.back().get());
}

btRigidBody* BinWorld::add_part(const btTransform& body_pose) {
  btRigidBody::btRigidBodyConstructionInfo info(1, nullptr, part_.shape(),
                                                part_.inertia_per_mass());
  info.m_startWorldTransform = body_pose;
  info.m_friction = btScalar(options_.friction);
  info.m_restitution = btScalar(options_.restitution);
  info.m_rollingFriction = info.m_spinningFriction = rolling_friction_;
  info.m_linearSleepingThreshold = btScalar(options_.rest_linear_speed_mm_s / kMmPerUnit);
  info.m_angularSleepingThreshold = btScalar(options_.rest_angular_speed_rad_s);
  part_bodies_.push_back(std::make_unique<btRigidBody>(info));
  btRigidBody* body = part_bodies_.back().get();
  body->setUserIndex(static_cast<int>(parts_.size()));
  parts_.push_back(body);
  rest_.add();
  world_.addRigidBody(body);
  return body;
}

double BinWorld::next_step_length() const {
  // Fastest point of any moving part: centre speed plus spin times radius.
  const double radius = part_.bounding_radius_mm() / kMmPerUnit;
  double fastest = 0.0;
  for (const btRigidBody* body : parts_)
    if (body->isInWorld() && body->isActive() && !body->isStaticObject())
      fastest = std::max(fastest, double(body->getLinearVelocity().length()) +
                                      body->getAngularVelocity().length() * radius);
  const double travel = options_.step_travel * part_.thinnest_mm() / kMmPerUnit;
  const double longest = options_.time_step_s;
  if (fastest * longest <= travel) return longest;
  return std::max(travel / fastest, longest / kMaxStepDivision);
}

double BinWorld::step() {
  const double dt = next_step_length();
  world_.stepSimulation(btScalar(dt), 0);
  for (const btRigidBody* body : parts_)
    if (body->isInWorld() && !body->isStaticObject())
      rest_.update(body->getUserIndex(), body->getLinearVelocity(), body->getAngularVelocity(), dt);
  return dt;
}

bool BinWorld::at_rest(const btRigidBody& body) const {
  return frozen(body) || body.getUserIndex() < 0 || body.getActivationState() == ISLAND_SLEEPING ||
         rest_.at_rest(body.getUserIndex());
}

double BinWorld::speed_ratio(const btRigidBody& body) const {
  return frozen(body) || body.getUserIndex() < 0 ? 0.0 : rest_.speed_ratio(body.getUserIndex());
}

void BinWorld::freeze(btRigidBody* body) {
  // Bullet sorts bodies into static and dynamic lists and collision groups when they are
  // added, so a body changes kind by leaving and re-entering the world.
  world_.removeRigidBody(body);
  body->setMassProps(0, btVector3(0, 0, 0));  // also flags it static
  body->setLinearVelocity(btVector3(0, 0, 0));
  body->setAngularVelocity(btVector3(0, 0, 0));
  body->updateInertiaTensor();
  world_.addRigidBody(body);
}

void BinWorld::thaw(btRigidBody* body) {
  world_.removeRigidBody(body);
  body->setMassProps(1, part_.inertia_per_mass());  // also clears the static flag
  body->updateInertiaTensor();
  world_.addRigidBody(body);
  body->activate(true);
  rest_.restart(body->getUserIndex());
}

void BinWorld::remove(btRigidBody* body) { world_.removeRigidBody(body); }

}  // namespace binpick
