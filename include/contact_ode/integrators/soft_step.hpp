#pragma once
// Box2D v3's soft contact constraint (Catto, "Solver2D" and "Soft Step", 2024): a contact as a
// spring-damper of natural frequency w = 2 pi hertz and damping ratio zeta, solved implicitly at
// the velocity level. For a sub-step h:
//   a1 = 2 zeta + h w,  a2 = h w a1,  a3 = 1 / (1 + a2),
//   bias_rate = w / a1,  mass_scale = a2 a3,  impulse_scale = a3,
// and the impulse on a contact of effective inverse mass w_n, gap rate u, separation s < 0 and
// impulse so far L is
//   dL = -(mass_scale / w_n) (u + max(bias_rate s, -push_max)) - impulse_scale L,
// the push-out speed bias_rate |s| capped at push_max (Box2D's contactPushMaxVelocity).
// From L = 0 this is exactly implicit (backward) Euler on u' = -w^2 s - 2 zeta w u with s moved
// by h u': u+ (1 + 2 zeta w h + w^2 h^2) = u - h w^2 s. The soft constraint is the implicit
// Euler spring of stiffness k = w^2 / w_n and dashpot c = 2 zeta w / w_n.
#include <limits>

namespace contact {

struct SoftConstraint {
  double bias_rate;      // [1/s]
  double mass_scale;     // [1]
  double impulse_scale;  // [1]
};

SoftConstraint soft_constraint(double hertz, double zeta, double h);

// The soft impulse increment above, for a contact of effective inverse mass w_n [1/kg], gap rate
// u [m/s], separation s [m] (< 0 overlapping), accumulated impulse L [N s] and push-out cap
// push_max [m/s] (infinite: none).
double soft_impulse(const SoftConstraint& c, double w_n, double u, double s, double L,
                    double push_max = std::numeric_limits<double>::infinity());

}  // namespace contact
