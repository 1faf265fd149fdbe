#include "fixed_step.hpp"

namespace contact {

std::string_view to_string(FixedStepScheme s) {
  switch (s) {
    case FixedStepScheme::ExplicitEuler: return "explicit-euler";
    case FixedStepScheme::SemiImplicitEuler: return "semi-implicit-euler";
    case FixedStepScheme::VelocityVerlet: return "velocity-verlet";
    case FixedStepScheme::Rk4: return "rk4";
  }
  return "?";
}

int fixed_step(FixedStepScheme scheme, const OdeSystem::Rhs& f, std::size_t position_size,
               double t, double h, VectorRef y, FixedStepWork& w) {
  const auto nq = static_cast<Eigen::Index>(position_size);
  const auto nv = y.size() - nq;
  switch (scheme) {
    case FixedStepScheme::ExplicitEuler:
      f(t, y, w.k1);
      y += h * w.k1;
      return 1;
    case FixedStepScheme::SemiImplicitEuler:
      f(t, y, w.k1);
      y.tail(nv) += h * w.k1.tail(nv);
      f(t, y, w.k1);  // position rates from the updated velocities
      y.head(nq) += h * w.k1.head(nq);
      return 2;
    case FixedStepScheme::VelocityVerlet:
      f(t, y, w.k1);
      y.tail(nv) += 0.5 * h * w.k1.tail(nv);
      f(t + 0.5 * h, y, w.k1);  // position rates at the half-step velocities
      y.head(nq) += h * w.k1.head(nq);
      f(t + h, y, w.k1);  // accelerations at the new positions
      y.tail(nv) += 0.5 * h * w.k1.tail(nv);
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
