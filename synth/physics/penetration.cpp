#include "synth/physics/penetration.hpp"

#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <memory>

#include "synth/physics/bullet_units.hpp"

namespace binpick {
namespace {

constexpr btScalar kMargin = btScalar(0.04);  // units, Bullet's default

}  // namespace

double deepest_penetration_mm(const ConvexParts& hulls,
                              const std::vector<Eigen::Isometry3d>& poses) {
  // Bullet reports distances between margin-inflated shapes; its GJK/EPA misjudges exactly
  // coincident faces without a margin, so use one and take it off again.
  std::vector<std::unique_ptr<btConvexHullShape>> hull_shapes;
  btCompoundShape compound(true, static_cast<int>(hulls.hulls.size()));
  for (const auto& hull : hulls.hulls) {
    auto shape = std::make_unique<btConvexHullShape>();
    for (const auto& v : hull.vertices) shape->addPoint(to_units(v.cast<double>()), false);
    shape->recalcLocalAabb();
    shape->setMargin(kMargin);
    compound.addChildShape(btTransform::getIdentity(), shape.get());
    hull_shapes.push_back(std::move(shape));
  }
  compound.setMargin(kMargin);

  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btCollisionWorld world(&dispatcher, &broadphase, &configuration);
  std::vector<std::unique_ptr<btCollisionObject>> objects;
  for (const auto& pose : poses) {
    auto object = std::make_unique<btCollisionObject>();
    object->setCollisionShape(&compound);
    object->setWorldTransform(to_units(pose));
    world.addCollisionObject(object.get());
    objects.push_back(std::move(object));
  }
  world.performDiscreteCollisionDetection();

  double deepest = 0.0;
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    for (int c = 0; c < manifold->getNumContacts(); ++c)
      deepest =
          std::max(deepest, -double(manifold->getContactPoint(c).getDistance()) - 2 * kMargin);
  }
  for (auto& object : objects) world.removeCollisionObject(object.get());
  return deepest * kMmPerUnit;
}

}  // namespace binpick
