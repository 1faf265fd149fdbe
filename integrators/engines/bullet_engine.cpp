// Bullet 3.24 in double precision (libbullet-dev, bullet-float64) on the spheres-on-a-line
// scenes: btDiscreteDynamicsWorld with its sequential-impulse solver, spheres held to the axis by
// their linear factor (no rotation), the floor a static plane, no friction. Bullet's restitution
// of a contact is the product of its two bodies': the spheres carry sqrt(e) of the pairs and the
// floor the rest of its own. Two settings:
//   bullet         its defaults: contacts processed before they touch (processing threshold
//                  BT_LARGE_FLOAT), split impulses only beyond 4 cm of penetration, Baumgarte
//                  (erp2 0.2) in the velocities otherwise, no bounce below 0.2 m/s.
//   bullet-tuned   Newton's law: contacts processed only once they touch (threshold 0) and every
//                  overlap pushed out by split impulses (penetration threshold 0), so that the
//                  correction never feeds the bounce. The 0.2 m/s threshold is left as is.
#include "engine_world.hpp"

#include <btBulletDynamicsCommon.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace contact {

namespace {

btVector3 along(bool vertical, double x) { return vertical ? btVector3(0, 0, x) : btVector3(x, 0, 0); }

// 0 .. n-1 in the order of their bit-reversed indices (0, n/2, n/4, 3n/4, ...): each new index
// falls between two taken ones, as far from the last as the taken ones allow.
std::vector<std::size_t> bit_reversed_order(std::size_t n) {
  std::size_t width = 1, bits = 0;
  while (width < n) width <<= 1, ++bits;
  std::vector<std::size_t> order;
  order.reserve(n);
  for (std::size_t i = 0; i < width; ++i) {
    std::size_t r = 0;
    for (std::size_t k = 0; k < bits; ++k) r |= ((i >> k) & 1u) << (bits - 1 - k);
    if (r < n) order.push_back(r);
  }
  return order;
}

// Bullet's pools of contact manifolds and collision algorithms, sized to the scene: one of each a
// contact pair, twice over, up to its default of 4096, memory it writes through as it builds them
// (a millisecond of every small world's construction, 80 times what the rest took). A pool that
// runs out takes more from the heap (btCollisionDispatcher), so the size bounds no scene.
btDefaultCollisionConstructionInfo pools_for(const EngineScene& s) {
  btDefaultCollisionConstructionInfo info;
  const int size = static_cast<int>(std::min<std::size_t>(2 * s.law.size() + 2, 4096));
  info.m_defaultMaxPersistentManifoldPoolSize = size;
  info.m_defaultMaxCollisionAlgorithmPoolSize = size;
  return info;
}

class BulletWorld final : public EngineWorld {
 public:
  BulletWorld(const EngineScene& s, bool tuned)
      : scene_(s),
        configuration_(pools_for(s)),
        dispatcher_(&configuration_),
        sphere_(s.layout.radius),
        plane_(along(s.layout.vertical, 1.0), 0),
        world_(&dispatcher_, &broadphase_, &solver_, &configuration_) {
    const SphereLineLayout& l = s.layout;
    world_.setGravity(along(l.vertical, l.vertical ? -l.g : 0.0));
    if (tuned) world_.getSolverInfo().m_splitImpulsePenetrationThreshold = 0;
    const bool pairs = s.restitution.size() > (l.floor ? 1u : 0u);
    const double sphere_e = pairs ? std::sqrt(s.restitution.back()) : 1.0;
    if (l.floor) {
      // The floor's factor makes the product its own e. Spheres of e = 0 between them leave the
      // floor's contact at 0 whatever its factor (e / 0 was a NaN restitution, and a NaN state).
      double floor_e = s.restitution[0];
      if (sphere_e > 0)
        floor_e /= sphere_e;
      else if (floor_e > 0)
        throw EngineError(fmt::format(
            "Bullet multiplies the bodies' restitutions: spheres of e = 0 between them cannot meet the "
            "floor at e = {}",
            floor_e));
      floor_ = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &plane_));
      floor_->setRestitution(floor_e);
      floor_->setFriction(0);
      floor_->setUserIndex(-1);
      if (tuned) floor_->setContactProcessingThreshold(0);
      world_.addRigidBody(floor_.get());
    }
    for (std::size_t b = 0; b < l.mass.size(); ++b) {
      btVector3 inertia(0, 0, 0);
      sphere_.calculateLocalInertia(l.mass[b], inertia);
      auto body = std::make_unique<btRigidBody>(
          btRigidBody::btRigidBodyConstructionInfo(l.mass[b], nullptr, &sphere_, inertia));
      btTransform place;
      place.setIdentity();
      place.setOrigin(along(l.vertical, s.centre[b]) +
                      (l.vertical ? btVector3(0, 0, 0) : btVector3(0, 0, 1)));
      body->setWorldTransform(place);
      body->setLinearVelocity(along(l.vertical, s.velocity[b]));
      body->setLinearFactor(along(l.vertical, 1.0));
      body->setAngularFactor(0);
      body->setRestitution(sphere_e);
      body->setFriction(0);
      body->setActivationState(DISABLE_DEACTIVATION);
      body->setUserIndex(static_cast<int>(b));
      if (tuned) body->setContactProcessingThreshold(0);
      bodies_.push_back(std::move(body));
    }
    // Into the world in bit-reversed order, not along the line: Bullet's broadphase tree (btDbvt)
    // puts a new leaf beside the nearest, so spheres added in order grow a path as deep as the
    // line, and each insertion, and each step's update, walked it: a 64000-ball chain took 67 s
    // for one step (2.9 s now), 1e5 balls over 5 minutes (4.7 s). The order is the set-up's, not
    // the solver's settings; it does decide which contacts Bullet's sequential impulses visit
    // first. (Not Bullet's own rebuild, btDbvt::optimizeTopDown: it freed memory twice on a ball
    // 1e300 m up beside the floor's plane.)
    for (const std::size_t b : bit_reversed_order(bodies_.size())) world_.addRigidBody(bodies_[b].get());
  }
  // Bullet's teardown is quadratic in the bodies: removing one (removeRigidBody, or the world's
  // destructor for each of its objects) scans every overlapping pair, and the dynamics world's list
  // of bodies, for it. A 16000-ball chain spent 9 s here after one step; 1e5 balls did not end in
  // 5 minutes. The pairs are removed first, each in O(1) (a hashed cache), and then the world, which
  // the bodies outlive (declared before it), finds none left to scan for.
  ~BulletWorld() override {
    btOverlappingPairCache* pairs = broadphase_.getOverlappingPairCache();
    while (pairs->getNumOverlappingPairs() > 0) {
      const btBroadphasePair& last = pairs->getOverlappingPairArray()[pairs->getNumOverlappingPairs() - 1];
      pairs->removeOverlappingPair(last.m_pProxy0, last.m_pProxy1, &dispatcher_);
    }
  }
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  // One internal step of exactly h (maxSubSteps 0: Bullet steps by the time given).
  void step(double h) override { world_.stepSimulation(h, 0); }

  void read(std::vector<double>& centre, std::vector<double>& velocity) const override {
    centre.resize(bodies_.size());
    velocity.resize(bodies_.size());
    const bool v = scene_.layout.vertical;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      const btVector3 p = bodies_[b]->getWorldTransform().getOrigin(), u = bodies_[b]->getLinearVelocity();
      centre[b] = v ? p.z() : p.x();
      velocity[b] = v ? u.z() : u.x();
    }
  }

  // The impulses the solver applied to the manifolds' points in the last step (the split
  // impulses' pseudo-velocities are not among them). Only the points it processed: a point it
  // skipped (farther than the processing threshold) keeps the impulse of its last solve.
  void impulses(std::vector<double>& impulse) const override {
    std::fill(impulse.begin(), impulse.end(), 0.0);
    for (int k = 0; k < dispatcher_.getNumManifolds(); ++k) {
      const btPersistentManifold* m = dispatcher_.getManifoldByIndexInternal(k);
      const int c = scene_.contact_between(m->getBody0()->getUserIndex(), m->getBody1()->getUserIndex());
      if (c < 0) continue;
      for (int p = 0; p < m->getNumContacts(); ++p)
        if (m->getContactPoint(p).getDistance() <= m->getContactProcessingThreshold())
          impulse[static_cast<std::size_t>(c)] += m->getContactPoint(p).getAppliedImpulse();
    }
  }

 private:
  EngineScene scene_;
  btDefaultCollisionConfiguration configuration_;
  mutable btCollisionDispatcher dispatcher_;  // its manifold accessor is not const
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btSphereShape sphere_;
  btStaticPlaneShape plane_;
  // Before the world: destroyed after it, which still reads their proxies.
  std::unique_ptr<btRigidBody> floor_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  btDiscreteDynamicsWorld world_;
};

}  // namespace

// A Bullet world holds 531 doubles per state entry (chains of 5e4 and 1e5 balls).
constexpr double kBulletWorkingDoubles = 720;

std::vector<MethodInfo> bullet_methods() {
  return {
      engine_method("bullet",
                    "Bullet 3.24 (double) at its defaults: sequential impulses, Baumgarte, early contacts",
                    false, kBulletWorkingDoubles,
                    [](const EngineScene& s) { return std::make_unique<BulletWorld>(s, false); }),
      engine_method(
          "bullet-tuned",
          "Bullet 3.24 (double) tuned for Newton's law: contacts at touch, split impulses at any overlap",
          false, kBulletWorkingDoubles,
          [](const EngineScene& s) { return std::make_unique<BulletWorld>(s, true); })};
}

}  // namespace contact
