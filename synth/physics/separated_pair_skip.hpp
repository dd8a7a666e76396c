// Skips Bullet's contact test between two convex hulls that are clearly apart. Bullet tests
// every pair of hulls whose boxes overlap, every step, from scratch (GJK, no memory of the last
// step): in a 350-part bin of the built-in tee, 80 % of those tests (hulls of parts lying side
// by side, their boxes overlapping, the hulls not) found no contact, and GJK was half of the
// drop's time. This remembers, per pair of hulls, an axis along which they were apart; while a
// pair has no contact point and its hulls stay farther apart along that axis than the manifold
// keeps points at, Bullet's test could add nothing, so it is not run. Otherwise Bullet's
// algorithm runs unchanged. The gap along any axis is a lower bound of the distance, so the
// simulation is the same, bit for bit: the 350-part bins of the built-in parts take 6 to 27 %
// less CPU time, the tee's 31 to 33 s instead of 42 to 43 (docs/synthesis.md). The distances at which
// Bullet keeps points were read off Bullet 3.24; tests/synth/test_separated_pair_skip.cpp
// compares bins with and without the skip, so another Bullet that keeps points farther fails it.
#pragma once

#include <btBulletCollisionCommon.h>

namespace binpick {

// Registered in place of Bullet's convex-convex algorithm for the shape pairs given; wraps the
// algorithm the collision configuration would have used.
class SeparatedPairSkip : public btCollisionAlgorithmCreateFunc {
 public:
  // Wraps `configuration`'s algorithm for hull-hull and hull-box pairs, and registers itself
  // with `dispatcher` for them. Must outlive every algorithm it creates (the world's pairs).
  SeparatedPairSkip(btCollisionConfiguration& configuration, btCollisionDispatcher& dispatcher);

  // Contact tests of wrapped pairs, and how many of them were skipped.
  struct Counts {
    long long tests = 0;
    long long skipped = 0;
  };
  const Counts& counts() const { return counts_; }

  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& info,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override;

 private:
  btCollisionConfiguration& configuration_;
  Counts counts_;
};

}  // namespace binpick
