#include "synth/physics/separated_pair_skip.hpp"

#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include <algorithm>
#include <new>

namespace binpick {
namespace {

// Float rounding in Bullet's GJK and in the gap below: a pair is skipped only this far (units)
// beyond the distance at which Bullet could report a contact.
constexpr btScalar kSlack = btScalar(1e-3);
// After the n-th GJK in a row that found the hulls too close (n at most this), the next 2^n - 1
// tests go straight to Bullet: hulls in contact, or about to be, would fail it step after step.
constexpr int kMaxMisses = 4;

const btConvexShape& convex(const btCollisionObjectWrapper* body) {
  return *static_cast<const btConvexShape*>(body->getCollisionShape());
}

bool has_polyhedron(const btCollisionObjectWrapper* body) {
  const btCollisionShape* shape = body->getCollisionShape();
  return shape->isPolyhedral() &&
         static_cast<const btPolyhedralConvexShape*>(shape)->getConvexPolyhedron() != nullptr;
}

// How far apart the two shapes' cores (without margins, as GJK sees them) lie along `axis`
// (world, pointing from a to b): a lower bound of their distance, negative if they overlap
// along it.
btScalar gap_along(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b,
                   const btVector3& axis) {
  const btTransform& ta = a->getWorldTransform();
  const btTransform& tb = b->getWorldTransform();
  const btVector3 on_a = ta(convex(a).localGetSupportingVertexWithoutMargin(axis * ta.getBasis()));
  const btVector3 on_b = tb(convex(b).localGetSupportingVertexWithoutMargin(-axis * tb.getBasis()));
  return axis.dot(on_b - on_a);
}

class SkippingAlgorithm : public btCollisionAlgorithm {
 public:
  SkippingAlgorithm(const btCollisionAlgorithmConstructionInfo& info,
                    btConvexConvexAlgorithm* bullet, SeparatedPairSkip::Counts& counts)
      : btCollisionAlgorithm(info), bullet_(bullet), counts_(counts) {}

  ~SkippingAlgorithm() override {
    bullet_->~btConvexConvexAlgorithm();
    m_dispatcher->freeCollisionAlgorithm(bullet_);
  }

  void processCollision(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                        btManifoldResult* result) override {
    // Bullet's algorithm makes the pair's manifold on its first call; the manifolds' order in
    // the dispatcher orders the solver's work, so it must be made at the same step as before.
    ++counts_.tests;
    auto* manifold = const_cast<btPersistentManifold*>(bullet_->getManifold());
    if (manifold && manifold->getNumContacts() == 0 && apart(body0, body1, *manifold, *result)) {
      ++counts_.skipped;
      // What Bullet does when GJK finds the hulls farther apart than it reports contacts at.
      result->setPersistentManifold(manifold);
      result->refreshContactPoints();
      return;
    }
    bullet_->processCollision(body0, body1, info, result);
  }

  btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
                                 const btDispatcherInfo& info, btManifoldResult* result) override {
    return bullet_->calculateTimeOfImpact(body0, body1, info, result);
  }

  void getAllContactManifolds(btManifoldArray& manifolds) override {
    bullet_->getAllContactManifolds(manifolds);
  }

 private:
  // Whether Bullet's test of the pair would leave its empty manifold empty: the manifold takes
  // no point farther than its breaking threshold. Between two hulls with polyhedral features
  // (part_shape.cpp) btConvexConvexAlgorithm reports points at the distance of the cores;
  // otherwise (a hull and the bin's boxes) at the cores' distance less both margins.
  bool apart(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
             const btPersistentManifold& manifold, const btManifoldResult& result) {
    const btScalar margins =
        has_polyhedron(body0) && has_polyhedron(body1)
            ? btScalar(0)
            : convex(body0).getMargin() + convex(body1).getMargin();
    const btScalar needed = margins + manifold.getContactBreakingThreshold() +
                            result.m_closestPointDistanceThreshold + kSlack;
    if (has_axis_ && gap_along(body0, body1, axis_) > needed) return true;
    // After a miss, wait a few tests, longer after each miss, before running GJK again.
    if (wait_ > 0) {
      --wait_;
      return false;
    }
    // The remembered axis no longer separates them far enough: GJK's closest direction now.
    btVoronoiSimplexSolver simplex;
    btGjkPairDetector gjk(&convex(body0), &convex(body1), &simplex, nullptr);
    gjk.setIgnoreMargin(true);
    struct NoPoints : btDiscreteCollisionDetectorInterface::Result {
      void setShapeIdentifiersA(int, int) override {}
      void setShapeIdentifiersB(int, int) override {}
      void addContactPoint(const btVector3&, const btVector3&, btScalar) override {}
    } ignored;
    btGjkPairDetector::ClosestPointInput input;
    input.m_transformA = body0->getWorldTransform();
    input.m_transformB = body1->getWorldTransform();
    gjk.getClosestPoints(input, ignored, nullptr);
    btVector3 axis = gjk.getCachedSeparatingAxis();  // zero when the cores overlap
    has_axis_ = axis.length2() > SIMD_EPSILON;
    if (has_axis_) {
      axis.normalize();
      // GJK's axis points from b to a; either way, the sign that separates.
      axis_ = gap_along(body0, body1, -axis) > gap_along(body0, body1, axis) ? -axis : axis;
    }
    const bool apart = has_axis_ && gap_along(body0, body1, axis_) > needed;
    misses_ = apart ? 0 : std::min(misses_ + 1, kMaxMisses);
    wait_ = (1 << misses_) - 1;
    return apart;
  }

  btConvexConvexAlgorithm* bullet_;
  SeparatedPairSkip::Counts& counts_;
  btVector3 axis_{0, 0, 0};  // unit, world, from body0's shape towards body1's
  bool has_axis_ = false;
  int misses_ = 0;
  int wait_ = 0;
};

// Bullet's pool hands out blocks the size of its largest algorithm, unchecked in release builds.
static_assert(sizeof(SkippingAlgorithm) <= sizeof(btConvexConvexAlgorithm));

}  // namespace

SeparatedPairSkip::SeparatedPairSkip(btCollisionConfiguration& configuration,
                                     btCollisionDispatcher& dispatcher)
    : configuration_(configuration) {
  dispatcher.registerCollisionCreateFunc(CONVEX_HULL_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE,
                                         this);
  dispatcher.registerCollisionCreateFunc(CONVEX_HULL_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE, this);
  dispatcher.registerCollisionCreateFunc(BOX_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE, this);
}

btCollisionAlgorithm* SeparatedPairSkip::CreateCollisionAlgorithm(
    btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* body0,
    const btCollisionObjectWrapper* body1) {
  btCollisionAlgorithm* bullet =
      configuration_
          .getCollisionAlgorithmCreateFunc(body0->getCollisionShape()->getShapeType(),
                                           body1->getCollisionShape()->getShapeType())
          ->CreateCollisionAlgorithm(info, body0, body1);
  auto* convex_convex = dynamic_cast<btConvexConvexAlgorithm*>(bullet);
  if (!convex_convex) return bullet;
  void* memory = info.m_dispatcher1->allocateCollisionAlgorithm(sizeof(SkippingAlgorithm));
  return new (memory) SkippingAlgorithm(info, convex_convex, counts_);
}

}  // namespace binpick
