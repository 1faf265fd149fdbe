#pragma once
// The tutorial's collision response on a rigid contact.
//   restitution   e = elasticity_a * elasticity_b
//   projection    separate along the normal by the penetration: equal split (the tutorial's first,
//                 naive version; a body of infinite mass does not move and the other takes all),
//                 or by inverse-mass share (a moves -n p m_a^-1 / (m_a^-1 + m_b^-1), b the rest)
//   impulse       v_r = (v_b + w_b x r_b) - (v_a + w_a x r_a),
//                 J = -(1 + e) v_r.n / (m_a^-1 + m_b^-1 + [I_a^-1 (r_a x n) x r_a + I_b^-1 (r_b x n) x
//                 r_b].n), v_a -= m_a^-1 J n, w_a -= I_a^-1 (r_a x J n), v_b += m_b^-1 J n, w_b += I_b^-1
//                 (r_b x J n), applied only while approaching (v_r.n < 0): on a separating contact it would
//                 pull the bodies back together.
#include "contact_ode/models/rigid/rigid_contacts.hpp"

namespace contact::rigid {

enum class ProjectionShare { Equal, InverseMass };

double pair_restitution(const RigidBody& a, const RigidBody& b);
void project(std::span<RigidBody> bodies, const RigidContact& c, ProjectionShare share);
// Returns the impulse magnitude J (0 when the contact does not approach).
double apply_impulse(std::span<RigidBody> bodies, const RigidContact& c, double e);
// The contact's normal inverse mass m_a^-1 + m_b^-1 + the angular terms above [1/kg].
double normal_inverse_mass(std::span<const RigidBody> bodies, const RigidContact& c);
// The impulse J n at the contact: b gets +J n, a gets -J n, linear and angular.
void apply_normal_impulse(std::span<RigidBody> bodies, const RigidContact& c, double J);
// The same map on the positions (XPBD): b moves by m_b^-1 d n and turns by I_b^-1 (r_b x d n),
// a the opposite; orientations turn by that small rotation and are renormalised.
void apply_normal_displacement(std::span<RigidBody> bodies, const RigidContact& c, double d);
// The relative normal velocity v_r.n at the contact (< 0 approaching).
double normal_velocity(std::span<const RigidBody> bodies, const RigidContact& c);

}  // namespace contact::rigid
