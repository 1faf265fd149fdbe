#include "fixed_step.hpp"

namespace contact {

std::string_view to_string(FixedStepScheme s) {
  return s == FixedStepScheme::ExplicitEuler ? "explicit-euler" : "semi-implicit-euler";
}

int fixed_step(FixedStepScheme scheme, const OdeSystem::Rhs& f, std::size_t position_size,
               double t, double dt, VectorRef y, Vector& work) {
  const auto nq = static_cast<Eigen::Index>(position_size);
  const auto nv = y.size() - nq;
  f(t, y, work);
  if (scheme == FixedStepScheme::ExplicitEuler) {
    y += dt * work;
    return 1;
  }
  y.tail(nv) += dt * work.tail(nv);
  f(t, y, work);  // position rates from the updated velocities
  y.head(nq) += dt * work.head(nq);
  return 2;
}

}  // namespace contact
