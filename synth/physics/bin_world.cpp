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
    : BinWorld(options, std::vector<const PartShape*>{&part}) {}

BinWorld::BinWorld(const DropOptions& options, std::vector<const PartShape*> kinds)
    : options_(options),
      kinds_(std::move(kinds)),
      // Bullet multiplies the two bodies' coefficients of a contact.
      rolling_friction_(btScalar(std::sqrt(options.rolling_friction_mm / kMmPerUnit))),
      rest_(options.rest_linear_speed_mm_s / kMmPerUnit, options.rest_angular_speed_rad_s,
            options.rest_seconds) {
  if (options.skip_apart_hulls)
    skip_apart_ = std::make_unique<SeparatedPairSkip>(collision_configuration_, dispatcher_);
  world_.setGravity(btVector3(0, 0, btScalar(-kGravityUnits)));
  contact_erp_ = world_.getSolverInfo().m_erp2;
  // Bullet puts an island to sleep once all its bodies have been below their sleeping
  // thresholds this long; the same duration as our own rest test. (A process-wide global:
  // written only when it changes, so that bins dropping side by side only read it.)
  if (gDeactivationTime != btScalar(options.rest_seconds))
    gDeactivationTime = btScalar(options.rest_seconds);

  thinnest_mm_ = INFINITY;
  for (const PartShape* k : kinds_) thinnest_mm_ = std::min(thinnest_mm_, k->thinnest_mm());
  // A stack of sheets has little to sink before one passes through another (drop.hpp).
  world_.getSolverInfo().m_numIterations =
      sheet_pile() ? std::max(options.solver_iterations, options.sheet_solver_iterations)
                   : options.solver_iterations;

  const auto bin = bin_of(options);
  if (bin->boxes.empty()) {
    add_static_mesh(bin->mesh);
  } else {
    for (const Eigen::AlignedBox3d& box : bin->boxes)
      add_static_box(to_units(Eigen::Vector3d(box.sizes() / 2)),
                     to_units(Eigen::Vector3d(box.center())));
  }
  // The ground under the bin reaches well past it, so a part thrown out lands and comes to
  // rest (and is reported) instead of falling forever. The camera does not see it.
  const btVector3 lo = to_units(Eigen::Vector3d(bin->bounds.min()));
  const btVector3 hi = to_units(Eigen::Vector3d(bin->bounds.max()));
  const btVector3 reach = (hi - lo) * btScalar(1.5) + btVector3(10, 10, 0);
  const btScalar g = kGroundThickness;
  add_static_box(btVector3(reach.x(), reach.y(), g / 2),
                 btVector3((lo.x() + hi.x()) / 2, (lo.y() + hi.y()) / 2, lo.z() - g / 2));
  lost_below_ = lo.z() - g;
}

BinWorld::~BinWorld() {
  for (auto& body : part_bodies_)
    if (body->isInWorld()) world_.removeRigidBody(body.get());
  for (auto& body : static_bodies_) world_.removeRigidBody(body.get());
}

void BinWorld::add_static_box(const btVector3& half_extents, const btVector3& centre) {
  static_shapes_.push_back(std::make_unique<btBoxShape>(half_extents));
  add_static(static_shapes_.back().get(), centre);
}

void BinWorld::add_static_mesh(const Mesh& mesh) {
  for (const auto& p : mesh.positions)
    for (int k = 0; k < 3; ++k) mesh_vertices_.push_back(float(p[k] / kMmPerUnit));
  for (const auto& t : mesh.triangles)
    for (const std::uint32_t i : t) mesh_indices_.push_back(int(i));
  mesh_arrays_ = std::make_unique<btTriangleIndexVertexArray>(
      int(mesh.triangles.size()), mesh_indices_.data(), int(3 * sizeof(int)),
      int(mesh.positions.size()), mesh_vertices_.data(), int(3 * sizeof(float)));
  static_shapes_.push_back(std::make_unique<btBvhTriangleMeshShape>(mesh_arrays_.get(), true));
  add_static(static_shapes_.back().get(), btVector3(0, 0, 0));
}

void BinWorld::add_static(btCollisionShape* shape, const btVector3& centre) {
  btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shape);
  info.m_startWorldTransform.setIdentity();
  info.m_startWorldTransform.setOrigin(centre);
  info.m_friction = btScalar(options_.friction);
  info.m_restitution = btScalar(options_.restitution);
  info.m_rollingFriction = info.m_spinningFriction = rolling_friction_;
  static_bodies_.push_back(std::make_unique<btRigidBody>(info));
  world_.addRigidBody(static_bodies_.back().get());
}

btRigidBody* BinWorld::add_part(const btTransform& body_pose, int kind) {
  const PartShape& part = shape(kind);
  btRigidBody::btRigidBodyConstructionInfo info(1, nullptr, part.shape(), part.inertia_per_mass());
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
  kinds_of_parts_.push_back(kind);
  rest_.add(body_pose);
  world_.addRigidBody(body);
  return body;
}

double BinWorld::next_step_length() const {
  // Fastest point of any moving part: centre speed plus spin times radius.
  double fastest = 0.0;
  for (const btRigidBody* body : parts_)
    if (body->isInWorld() && body->isActive() && !body->isStaticObject())
      fastest = std::max(fastest, double(body->getLinearVelocity().length()) +
                                      body->getAngularVelocity().length() *
                                          shape(kind(*body)).bounding_radius_mm() / kMmPerUnit);
  const double travel = options_.step_travel * thinnest_mm_ / kMmPerUnit;
  const double longest = options_.time_step_s;
  if (fastest * longest <= travel) return longest;
  return std::max(travel / fastest, longest / kMaxStepDivision);
}

double BinWorld::step() {
  const double dt = next_step_length();
  // Bullet corrects a penetration by the fraction erp2 of its depth per step, as a velocity
  // (or, when deep, a position push) of erp2 * depth / dt. When the adaptive step shrinks to a
  // twentieth, every resting contact of the pile is pushed apart twenty times as fast: in a
  // pile of plates a landing wave then shook the layers below by millimetres, which woke them
  // (pile_freezer.hpp), and their speeds kept the step short. Scaled with the step, the
  // correction takes the same time in seconds whatever the step; unchanged at the full step.
  world_.getSolverInfo().m_erp2 = btScalar(contact_erp_ * dt / options_.time_step_s);
  world_.stepSimulation(btScalar(dt), 0);
  for (const btRigidBody* body : parts_)
    if (body->isInWorld() && !body->isStaticObject())
      rest_.update(body->getUserIndex(), body->getWorldTransform(), dt);
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
  body->setMassProps(1, shape(kind(*body)).inertia_per_mass());  // also clears the static flag
  body->updateInertiaTensor();
  world_.addRigidBody(body);
  body->activate(true);
  rest_.restart(body->getUserIndex(), body->getWorldTransform());
}

bool BinWorld::touching(btRigidBody& a, btRigidBody& b, btScalar within) {
  struct Closest : btCollisionWorld::ContactResultCallback {
    bool close = false;
    btScalar addSingleResult(btManifoldPoint& point, const btCollisionObjectWrapper*, int, int,
                             const btCollisionObjectWrapper*, int, int) override {
      close = close || point.getDistance() < m_closestDistanceThreshold;
      return 0;
    }
  } result;
  result.m_closestDistanceThreshold = within;
  world_.contactPairTest(&a, &b, result);
  return result.close;
}

void BinWorld::remove(btRigidBody* body) { world_.removeRigidBody(body); }

}  // namespace binpick
