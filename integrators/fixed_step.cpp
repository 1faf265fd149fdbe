#include "contact_ode/integrators/fixed_step.hpp"

namespace contact {

std::string_view to_string(FixedStepScheme s) {
  switch (s) {
    case FixedStepScheme::ExplicitEuler:
      return "explicit-euler";
    case FixedStepScheme::SemiImplicitEuler:
      return "semi-implicit-euler";
    case FixedStepScheme::VelocityVerlet:
      return "velocity-verlet";
    case FixedStepScheme::Rk4:
      return "rk4";
  }
  return "?";
}

int fixed_step(FixedStepScheme scheme, const OdeSystem::Rhs& f, const Mask& q, double t, double h,
               VectorRef y, FixedStepWork& w) {
  // Updates of the positions only, or of the velocities only, by h times the rates in k.
  auto move_positions = [&](double h_, const Vector& k) {
    y = q.select((y + h_ * k).array(), y.array()).matrix();
  };
  auto move_velocities = [&](double h_, const Vector& k) {
    y = q.select(y.array(), (y + h_ * k).array()).matrix();
  };
  switch (scheme) {
    case FixedStepScheme::ExplicitEuler:
      f(t, y, w.k1);
      y += h * w.k1;
      return 1;
    case FixedStepScheme::SemiImplicitEuler:
      f(t, y, w.k1);
      move_velocities(h, w.k1);
      f(t, y, w.k1);  // position rates from the updated velocities
      move_positions(h, w.k1);
      return 2;
    case FixedStepScheme::VelocityVerlet:
      f(t, y, w.k1);
      move_velocities(0.5 * h, w.k1);
      f(t + 0.5 * h, y, w.k1);  // position rates at the half-step velocities
      move_positions(h, w.k1);
      f(t + h, y, w.k1);  // accelerations at the new positions
      move_velocities(0.5 * h, w.k1);
      return 3;
    case FixedStepScheme::Rk4:
      f(t, y, w.k1);
      w.tmp = y + 0.5 * h * w.k1;
      f(t + 0.5 * h, w.tmp, w.k2);
      w.tmp = y + 0.5 * h * w.k2;
      f(t + 0.5 * h, w.tmp, w.k3);
      w.tmp = y + h * w.k3;
      f(t + h, w.tmp, w.k4);
      y += (h / 6.0) * (w.k1 + 2.0 * w.k2 + 2.0 * w.k3 + w.k4);
      return 4;
  }
  return 0;
}

}  // namespace contact
