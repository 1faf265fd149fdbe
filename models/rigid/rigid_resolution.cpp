#include "contact_ode/models/rigid/rigid_resolution.hpp"

namespace contact::rigid {

double pair_restitution(const RigidBody& a, const RigidBody& b) { return a.elasticity * b.elasticity; }

void project(std::vector<RigidBody>& bodies, const RigidContact& c, ProjectionShare share) {
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

double normal_velocity(const std::vector<RigidBody>& bodies, const RigidContact& c) {
  return (bodies[c.b].point_velocity(c.r_b) - bodies[c.a].point_velocity(c.r_a)).dot(c.normal);
}

double apply_impulse(std::vector<RigidBody>& bodies, const RigidContact& c, double e) {
  RigidBody &A = bodies[c.a], &B = bodies[c.b];
  const double vn = normal_velocity(bodies, c);
  if (vn >= 0) return 0.0;
  const Mat3 Ia = A.world_inverse_inertia(), Ib = B.world_inverse_inertia();
  const Vec3& n = c.normal;
  const double angular = ((Ia * c.r_a.cross(n)).cross(c.r_a) + (Ib * c.r_b.cross(n)).cross(c.r_b)).dot(n);
  const double denom = A.inverse_mass + B.inverse_mass + angular;
  if (denom <= 0) return 0.0;  // two immovable bodies
  const double J = -(1.0 + e) * vn / denom;
  A.velocity -= A.inverse_mass * J * n;
  B.velocity += B.inverse_mass * J * n;
  A.angular_velocity -= Ia * c.r_a.cross(J * n);
  B.angular_velocity += Ib * c.r_b.cross(J * n);
  return J;
}

}  // namespace contact::rigid
