// Rigid bodies: contact generation and the tutorial's projection and impulse (linear + angular).
//
// Conservation, derived: the impulse acts as +J n on b and -J n on a at the same world point p,
// so total linear momentum is unchanged, and about any fixed point O the angular momentum changes
// by (p - O) x J n - (p - O) x J n = 0 (each body's spin change I^-1 (r x J n) is exactly the
// moment of the impulse about its centre) -- for bodies whose lever arm is the true r = p - x.
// Kinetic energy: along n the impulse acts on the pair's effective inverse mass
// k = m_a^-1 + m_b^-1 + angular terms, changing the normal velocity from v to -e v; the energy
// change is -(1 - e^2) v^2 / (2k), zero for e = 1, and for a central impact (no angular terms)
// k = 1/mu: a loss of mu (1 - e^2) v^2 / 2 with mu = m_a m_b / (m_a + m_b).
// Tolerances: a handful of floating-point operations per quantity: 1e-13 relative.
#include "contact_ode/models/rigid/rigid_resolution.hpp"
#include "contact_ode/models/rigid/rigid_scene.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>

using namespace contact::rigid;

namespace {

constexpr double kTol = 1e-13;

Vec3 total_momentum(const std::vector<RigidBody>& bodies) {
  Vec3 p = Vec3::Zero();
  for (const auto& b : bodies) p += b.momentum();
  return p;
}
Vec3 total_angular_momentum(const std::vector<RigidBody>& bodies, const Vec3& about) {
  Vec3 L = Vec3::Zero();
  for (const auto& b : bodies) L += b.angular_momentum(about);
  return L;
}
double total_energy(const std::vector<RigidBody>& bodies) {
  double E = 0;
  for (const auto& b : bodies) E += b.kinetic_energy();
  return E;
}

// A spinning, moving cuboid whose corner touches a moving sphere: an off-centre, oblique contact.
// The sphere's centre lies off the corner's diagonal (anywhere in the corner's region, the octant
// beyond it), so the normal misses the box's centre and the impulse's angular terms are not zero:
// on the diagonal they were, and halving them went unnoticed here. The box is body `box_index`.
std::vector<RigidBody> corner_hit(std::mt19937& rng, double e_sphere, double e_box,
                                  std::size_t box_index = 0) {
  std::uniform_real_distribution<double> u(-1, 1), positive(0.2, 1);
  RigidBody box = RigidBody::cuboid("box", 2.0, Vec3(0.3, 0.2, 0.1), e_box);
  box.orientation = Quat(Eigen::AngleAxisd(u(rng) * 3, Vec3(u(rng), u(rng), u(rng)).normalized()));
  box.velocity = Vec3(u(rng), u(rng), u(rng));
  box.angular_velocity = Vec3(u(rng), u(rng), u(rng)) * 5;
  const Vec3 corner = vertices(box)[5];
  const Vec3 sign = (box.orientation.inverse() * (corner - box.position)).cwiseSign();
  const Vec3 out =
      box.orientation * sign.cwiseProduct(Vec3(positive(rng), positive(rng), positive(rng))).normalized();
  RigidBody ball = RigidBody::sphere("ball", 0.7, 0.05, e_sphere);
  ball.position = corner + out * 0.0499;  // overlapping the corner by 0.1 mm
  // Faster than the corner can move away (|v| <= sqrt 3, |w x r| <= 5 sqrt 3 * 0.37 = 3.2, the
  // ball's own 0.17: 5.1 at most): always approaching.
  ball.velocity = -out * 6 + Vec3(u(rng), u(rng), u(rng)) * 0.1;
  ball.angular_velocity = Vec3(u(rng), u(rng), u(rng));
  if (box_index == 0) return {box, ball};
  return {ball, box};
}

// How far the contact's normal passes from the box's centre, relative to its lever arm.
double off_centre(const RigidContact& c, std::size_t box_index) {
  const Vec3& r = box_index == 0 ? c.r_a : c.r_b;
  return r.cross(c.normal).norm() / r.norm();
}

}  // namespace

TEST(RigidImpulse, ConservesMomentaAndFollowsTheEnergyLaw) {
  std::mt19937 rng(7);
  double least_off_centre = 1;
  for (int trial = 0; trial < 100; ++trial) {
    for (double e : {1.0, 0.6, 0.0}) {
      const std::size_t box_index = trial % 2;
      auto bodies = corner_hit(rng, e, 1.0, box_index);
      const auto contacts = contact_candidates(bodies, 0, 1);
      ASSERT_EQ(contacts.size(), 1u);
      const auto& c = contacts[0];
      ASSERT_GT(c.penetration, 0.0);
      least_off_centre = std::min(least_off_centre, off_centre(c, box_index));
      ASSERT_LT(normal_velocity(bodies, c), 0.0);
      const Vec3 p0 = total_momentum(bodies), L0 = total_angular_momentum(bodies, Vec3(1, -2, 3));
      const double E0 = total_energy(bodies);
      const double v = normal_velocity(bodies, c);
      const double J = apply_impulse(bodies, c, pair_restitution(bodies[0], bodies[1]));
      EXPECT_GT(J, 0.0);
      EXPECT_LT((total_momentum(bodies) - p0).norm(), kTol * (p0.norm() + J));
      EXPECT_LT((total_angular_momentum(bodies, Vec3(1, -2, 3)) - L0).norm(), kTol * 10 * (L0.norm() + J));
      // Newton's law at the contact point: v+ = -e v-.
      EXPECT_NEAR(normal_velocity(bodies, c), -e * v, kTol * 10 * std::abs(v));
      // Energy: -(1 - e^2) v^2 / (2k) with k = J / ((1 + e)|v|) (the effective inverse mass).
      const double k = (1 + e) * std::abs(v) / J;
      EXPECT_NEAR(total_energy(bodies) - E0, -(1 - e * e) * v * v / (2 * k), kTol * 10 * E0);
    }
  }
  // Every hit off the box's centre line (by the sine of the angle between its lever arm and the
  // normal), so that the angular terms count in each.
  EXPECT_GT(least_off_centre, 0.02);
}

// XPBD's position step: a normal displacement d moves body b by w_b d n and turns it by
// I_b^-1 (r_b x d n), body a the opposite way, so the contact's penetration falls by d times the
// effective inverse mass the impulse divides by, to first order in d. The second order is the
// turns' (|r| theta^2, theta ~ 1e-5 rad here) and the normal's tilt ((w d)^2 / radius): below 1e-4
// of the 1 um moved. The box is body a in half the trials and body b in the other half: its turn
// as body b had the wrong sign and nothing noticed (a sphere's turn moves no contact).
TEST(RigidProjection, ANormalDisplacementClosesTheGapByTheEffectiveInverseMass) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 100; ++trial) {
    auto bodies = corner_hit(rng, 1.0, 1.0, trial % 2);
    const auto c = contact_candidates(bodies, 0, 1)[0];
    const double w = normal_inverse_mass(bodies, c), moved = 1e-6;
    apply_normal_displacement(bodies, c, moved / w);
    EXPECT_NEAR(c.penetration - contact_candidates(bodies, 0, 1)[0].penetration, moved, 1e-4 * moved)
        << trial;
  }
}

TEST(RigidImpulse, CentralImpactLosesHalfMuOneMinusESquaredVSquared) {
  for (double e1 : {1.0, 0.9, 0.5}) {
    for (double e2 : {1.0, 0.8}) {
      RigidBody a = RigidBody::sphere("a", 0.17, 0.03, e1), b = RigidBody::sphere("b", 0.4, 0.03, e2);
      a.position = Vec3(0, 0, 0);
      b.position = Vec3(0.0599, 0, 0);
      a.velocity = Vec3(3, 0, 0);
      b.velocity = Vec3(-1, 0, 0);
      std::vector<RigidBody> bodies{a, b};
      const double E0 = total_energy(bodies), e = e1 * e2;
      apply_impulse(bodies, contact_candidates(bodies, 0, 1)[0], pair_restitution(bodies[0], bodies[1]));
      const double mu = 0.17 * 0.4 / (0.17 + 0.4), vrel = 4.0;
      EXPECT_NEAR(E0 - total_energy(bodies), 0.5 * mu * (1 - e * e) * vrel * vrel, kTol * E0);
      EXPECT_TRUE(bodies[0].angular_velocity.isZero(0));  // central: no spin
    }
  }
}

TEST(RigidImpulse, EqualMassesExchangeVelocitiesHeadOn) {
  RigidBody cue = RigidBody::sphere("cue", 0.17, 0.026, 1.0),
            red = RigidBody::sphere("red", 0.17, 0.026, 1.0);
  cue.velocity = Vec3(2.5, 0, 0);
  red.position = Vec3(0.052 - 1e-5, 0, 0);
  std::vector<RigidBody> bodies{cue, red};
  apply_impulse(bodies, contact_candidates(bodies, 0, 1)[0], pair_restitution(bodies[0], bodies[1]));
  EXPECT_NEAR(bodies[0].velocity.norm(), 0.0, 1e-15);
  EXPECT_NEAR((bodies[1].velocity - Vec3(2.5, 0, 0)).norm(), 0.0, 1e-15);
}

TEST(RigidImpulse, AxisAlignedBoxesNeverSpin) {
  std::vector<RigidBody> bodies{RigidBody::sphere("ball", 1.0, 0.1, 1.0),
                                RigidBody::aabb("crate", 3.0, Vec3(0.5, 0.5, 0.5), 1.0)};
  bodies[0].position = Vec3(0.55, 0.45, 0.3) + Vec3(0.09, 0, 0);  // beside a face, off-centre
  bodies[0].velocity = Vec3(-1, 0.2, 0);
  const auto c = contact_candidates(bodies, 0, 1)[0];
  EXPECT_TRUE(c.r_b.isZero(0));  // the tutorial's zero lever arm
  apply_impulse(bodies, c, 1.0);
  EXPECT_TRUE(bodies[1].angular_velocity.isZero(0));
  EXPECT_GT(bodies[1].velocity.norm(), 0.0);
}

// The solid bodies' inertias: a sphere's 2/5 m r^2 about every axis, a box's m (b^2 + c^2) / 12 about
// the axis of side a (sides a, b, c), in the body's frame whatever its orientation. No scene's
// motion showed them: the spheres are struck through their centres, and the boxes turned about one
// axis, so that a sphere's 1/2 or a box's sides swapped between two axes passed every other test.
TEST(RigidBody, InertiasAreTheSolidBodiesOnes) {
  const double m = 2.0, r = 0.5;
  RigidBody ball = RigidBody::sphere("ball", m, r, 1.0);
  ball.angular_velocity = Vec3(1, -2, 3);
  const double I = 0.4 * m * r * r;
  EXPECT_NEAR(ball.kinetic_energy(), 0.5 * I * 14.0, kTol * 7 * I);
  EXPECT_NEAR((ball.angular_momentum(ball.position) - I * ball.angular_velocity).norm(), 0.0, kTol * 4 * I);

  const Vec3 sides(0.2, 0.4, 0.6);
  RigidBody box = RigidBody::cuboid("box", m, sides / 2, 1.0);
  box.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, -1).normalized()));
  const Mat3 R = box.orientation.toRotationMatrix();
  for (int axis = 0; axis < 3; ++axis) {
    const int j = (axis + 1) % 3, k = (axis + 2) % 3;
    const double I_axis = m * (sides[j] * sides[j] + sides[k] * sides[k]) / 12;
    box.angular_velocity = 3.0 * R.col(axis);  // about the body's own axis
    EXPECT_NEAR(box.kinetic_energy(), 0.5 * I_axis * 9.0, kTol * 5 * I_axis) << "axis " << axis;
    EXPECT_NEAR((box.angular_momentum(box.position) - I_axis * box.angular_velocity).norm(), 0.0,
                kTol * 3 * I_axis)
        << "axis " << axis;
  }
}

TEST(RigidImpulse, SpinningBoxKnocksARestingSphere) {
  // No linear velocity anywhere: only the box's spin drives the contact (the tutorial's example).
  RigidBody box = RigidBody::cuboid("box", 1.0, Vec3(0.5, 0.1, 0.1), 1.0);
  box.angular_velocity = Vec3(0, 0, 4);  // the corner at (0.5, 0.1, .) moves along +y
  const Vec3 corner = vertices(box)[7];
  RigidBody ball = RigidBody::sphere("ball", 0.5, 0.1, 1.0);
  ball.position = corner + Vec3(0, 0.0999, 0);
  std::vector<RigidBody> bodies{box, ball};
  const auto c = contact_candidates(bodies, 0, 1)[0];
  EXPECT_LT(normal_velocity(bodies, c), 0.0);
  EXPECT_GT(apply_impulse(bodies, c, 1.0), 0.0);
  EXPECT_GT(bodies[1].velocity.y(), 0.0);
}

TEST(RigidContacts, GeometryOfEveryPair) {
  std::vector<RigidBody> b{RigidBody::sphere("s1", 1, 0.5, 1), RigidBody::sphere("s2", 1, 0.25, 1),
                           RigidBody::plane("floor", Vec3(0, 0, 1), 0.0, 1),
                           RigidBody::cuboid("box", 1, Vec3(1, 1, 1), 1)};
  b[0].position = Vec3(0, 0, 0.4);    // 0.1 into the floor
  b[1].position = Vec3(0.7, 0, 0.4);  // 0.05 into s1
  b[3].position = Vec3(0, 0, 5);
  auto ss = contact_candidates(b, 0, 1)[0];
  EXPECT_NEAR(ss.penetration, 0.05, 1e-15);
  EXPECT_TRUE(ss.normal.isApprox(Vec3(1, 0, 0)));
  auto sp = contact_candidates(b, 0, 2)[0];
  EXPECT_NEAR(sp.penetration, 0.1, 1e-15);
  EXPECT_TRUE(sp.normal.isApprox(Vec3(0, 0, -1)));  // from the sphere into the floor
  auto ps = contact_candidates(b, 2, 0)[0];
  EXPECT_TRUE(ps.normal.isApprox(Vec3(0, 0, 1)));
  EXPECT_EQ(ps.a, 2u);
  // Box at height 5 tilted about x by 45 degrees: its lowest edge's two vertices at 5 - sqrt(2).
  b[3].orientation = Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()));
  auto cp = contact_candidates(b, 3, 2);
  ASSERT_EQ(cp.size(), 8u);
  double lowest = -1e9;
  for (const auto& c : cp) lowest = std::max(lowest, c.penetration);
  EXPECT_NEAR(lowest, -(5 - std::sqrt(2.0)), 1e-14);
  // Sphere near a corner of an axis-aligned cube: the normal runs along the diagonal.
  b[3].orientation = Quat::Identity();
  b[1].position = b[3].position + Vec3(1, 1, 1) + Vec3(1, 1, 1).normalized() * 0.2;
  auto sc = contact_candidates(b, 1, 3)[0];
  EXPECT_NEAR(sc.penetration, 0.05, 1e-14);
  EXPECT_TRUE(sc.normal.isApprox(-Vec3(1, 1, 1).normalized()));
}

TEST(RigidProjection, InverseMassShareKeepsThePlanetStill) {
  RigidBody ball = RigidBody::sphere("ball", 1.0, 0.1, 1), planet = RigidBody::sphere("planet", 1e6, 10.0, 1);
  ball.position = Vec3(0, 0, 0);
  planet.position = Vec3(10.09, 0, 0);  // 0.01 overlap
  std::vector<RigidBody> bodies{ball, planet};
  const auto c = contact_candidates(bodies, 0, 1)[0];
  auto shared = bodies;
  project(shared, c, ProjectionShare::InverseMass);
  // A displacement read off positions near x = 10 carries their rounding, ~ulp(10) = 1.8e-15.
  EXPECT_NEAR((shared[1].position - planet.position).norm(), 0.01 * 1e-6 / (1 + 1e-6), 4e-15);
  EXPECT_NEAR(contact_candidates(shared, 0, 1)[0].penetration, 0.0, 1e-15);
  auto equal = bodies;
  project(equal, c, ProjectionShare::Equal);  // the tutorial's naive split moves the planet half
  EXPECT_NEAR((equal[1].position - planet.position).norm(), 0.005, 1e-15);
}

TEST(RigidBody, BadPropertiesAreRefusedByName) {
  EXPECT_THROW(RigidBody::sphere("ball", 0.0, 0.1, 1.0), std::invalid_argument);
  EXPECT_THROW(RigidBody::sphere("ball", 1.0, -0.1, 1.0), std::invalid_argument);
  EXPECT_THROW(RigidBody::cuboid("box", 1.0, Vec3(0.1, 0.0, 0.1), 1.0), std::invalid_argument);
  RigidBody b = RigidBody::sphere("ball", 1.0, 0.1, -0.5);
  try {
    b.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ball elasticity: value '-0.5'"), std::string::npos) << e.what();
  }
  b.elasticity = 1;
  b.orientation = Quat(0, 0, 0, 0);
  EXPECT_THROW(b.validate(), std::invalid_argument);
  b.orientation = Quat(std::nan(""), 0, 0, 1);
  EXPECT_THROW(b.validate(), std::invalid_argument);
  // A state entry that is not finite is named with its value (it was "ball state finite: value '0'").
  b.orientation = Quat(1, 0, 0, 0);
  b.velocity = Vec3(0, std::numeric_limits<double>::infinity(), 0);
  try {
    b.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ball velocity: value 'inf'"), std::string::npos) << e.what();
  }
}

// The fields a maker checks are public, so the scene checks them again: a shape set by hand, a
// plane given a mass (its geometry is its normal and offset: it cannot move), a static body given a
// velocity (its state has no derivatives: contacts would see a wall that moves and stays), an
// inertia that is not symmetric positive definite (it is inverted). Each was taken without a word.
TEST(RigidBody, ShapesPlanesInertiasAndStaticBodiesAreCheckedByName) {
  const auto refused = [](const RigidBody& b, const std::string& what) {
    try {
      b.validate();
      ADD_FAILURE() << "accepted: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  RigidBody ball = RigidBody::sphere("ball", 1.0, 0.1, 1.0);
  ball.shape = Sphere{-0.1};
  refused(ball, "ball radius: value '-0.1'");
  RigidBody box = RigidBody::cuboid("box", 1.0, Vec3(0.1, 0.2, 0.3), 1.0);
  box.shape = Cuboid{Vec3(0.1, std::nan(""), 0.3)};
  refused(box, "box half extent: value 'nan'");
  box = RigidBody::cuboid("box", 1.0, Vec3(0.1, 0.2, 0.3), 1.0);
  box.inverse_inertia(0, 1) = 1.0;
  refused(box, "box inverse inertia asymmetry: value '1'");
  box.inverse_inertia(1, 0) = 1.0e3;
  box.inverse_inertia(0, 1) = 1.0e3;  // symmetric, indefinite
  refused(box, "box inverse inertia's smallest eigenvalue");
  RigidBody floor = RigidBody::plane("floor", Vec3(0, 0, 2), 0.0, 1.0);
  EXPECT_NO_THROW(floor.validate());  // the maker normalises
  floor.inverse_mass = 1.0;
  refused(floor, "floor inverse mass (a plane): value '1'");
  floor.inverse_mass = 0.0;
  floor.shape = Plane{Vec3(0, 0, 2), 0.0};
  refused(floor, "floor plane normal length: value '2'");
  RigidBody wall = RigidBody::sphere("wall", 1.0, 0.1, 1.0);
  wall.inverse_mass = 0;
  EXPECT_NO_THROW(wall.validate());
  wall.velocity = Vec3(0, 3, 4);
  refused(wall, "wall speed (infinite mass): value '5'");
  wall.velocity.setZero();
  wall.angular_velocity = Vec3(0, 0, 2);
  refused(wall, "wall angular speed (infinite mass): value '2'");
}

// Two cuboids have no contact model: such a pair passed through each other without a word. A
// gravity that is not finite made every state NaN.
TEST(RigidBody, AScenesPairsAndGravityAreCheckedByName) {
  RigidBody a = RigidBody::cuboid("crate", 1.0, Vec3(0.1, 0.1, 0.1), 1.0),
            b = RigidBody::aabb("shelf", 1.0, Vec3(0.5, 0.1, 0.1), 1.0);
  b.position = Vec3(0, 0, -1);
  try {
    RigidScene("crates", {a, b}, Vec3(0, 0, -9.81), Hooke{1e6});
    ADD_FAILURE() << "two cuboids accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bodies 'crate' and 'shelf'"), std::string::npos) << e.what();
  }
  b.inverse_mass = 0;  // one static: the crate still falls through it
  EXPECT_THROW(RigidScene("crates", {a, b}, Vec3(0, 0, -9.81), Hooke{1e6}), std::invalid_argument);
  a.inverse_mass = 0;  // both static: they never meet
  EXPECT_EQ(RigidScene("crates", {a, b}, Vec3(0, 0, -9.81), Hooke{1e6}).contact_count(), 0u);
  try {
    RigidScene("crates", {a, b}, Vec3(0, 0, std::numeric_limits<double>::infinity()), Hooke{1e6});
    ADD_FAILURE() << "an infinite gravity accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scene 'crates' gravity: value 'inf'"), std::string::npos)
        << e.what();
  }
}
