#include "contact_ode/models/rigid/rigid_resolution.hpp"

namespace contact::rigid {

double pair_restitution(const RigidBody& a, const RigidBody& b) { return a.elasticity * b.elasticity; }

void project(std::span<RigidBody> bodies, const RigidContact& c, ProjectionShare share) {
  if (c.penetration <= 0) return;
  RigidBody &A = bodies[c.a], &B = bodies[c.b];
  const bool a_moves = A.inverse_mass > 0, b_moves = B.inverse_mass > 0;
  if (!a_moves && !b_moves) return;
  double share_a;
  if (share == ProjectionShare::Equal)
    share_a = a_moves && b_moves ? 0.5 : (a_moves ? 1.0 : 0.0);
  else
    share_a = A.inverse_mass / (A.inverse_mass + B.inverse_mass);
  A.position -= c.normal * (c.penetration * share_a);
  B.position += c.normal * (c.penetration * (1.0 - share_a));
}

double normal_velocity(std::span<const RigidBody> bodies, const RigidContact& c) {
  return (bodies[c.b].point_velocity(c.r_b) - bodies[c.a].point_velocity(c.r_a)).dot(c.normal);
}

double normal_inverse_mass(std::span<const RigidBody> bodies, const RigidContact& c) {
  const RigidBody &A = bodies[c.a], &B = bodies[c.b];
  const Mat3 Ia = A.world_inverse_inertia(), Ib = B.world_inverse_inertia();
  const Vec3& n = c.normal;
  const double angular = ((Ia * c.r_a.cross(n)).cross(c.r_a) + (Ib * c.r_b.cross(n)).cross(c.r_b)).dot(n);
  return A.inverse_mass + B.inverse_mass + angular;
}

void apply_normal_impulse(std::span<RigidBody> bodies, const RigidContact& c, double J) {
  RigidBody &A = bodies[c.a], &B = bodies[c.b];
  const Vec3 Jn = J * c.normal;
  A.velocity -= A.inverse_mass * Jn;
  B.velocity += B.inverse_mass * Jn;
  A.angular_velocity -= A.world_inverse_inertia() * c.r_a.cross(Jn);
  B.angular_velocity += B.world_inverse_inertia() * c.r_b.cross(Jn);
}

void apply_normal_displacement(std::span<RigidBody> bodies, const RigidContact& c, double d) {
  const Vec3 dn = d * c.normal;
  auto turn = [](RigidBody& body, const Vec3& angle) {
    const Quat dq(0.0, angle.x(), angle.y(), angle.z());
    body.orientation.coeffs() += 0.5 * (dq * body.orientation).coeffs();
    body.orientation.normalize();
  };
  RigidBody &A = bodies[c.a], &B = bodies[c.b];
  const Vec3 turn_a = -(A.world_inverse_inertia() * c.r_a.cross(dn)),
             turn_b = B.world_inverse_inertia() * c.r_b.cross(dn);
  A.position -= A.inverse_mass * dn;
  B.position += B.inverse_mass * dn;
  turn(A, turn_a);
  turn(B, turn_b);
}

double apply_impulse(std::span<RigidBody> bodies, const RigidContact& c, double e) {
  const double vn = normal_velocity(bodies, c);
  if (vn >= 0) return 0.0;
  const double denom = normal_inverse_mass(bodies, c);
  if (denom <= 0) return 0.0;  // two immovable bodies
  const double J = -(1.0 + e) * vn / denom;
  apply_normal_impulse(bodies, c, J);
  return J;
}

}  // namespace contact::rigid
