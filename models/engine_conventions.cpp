#include "contact_ode/models/engine_conventions.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace contact {

// The root of each factor: k m underflowed for 1e-300 kg on 1e-295 N/m (the ratio came out NaN).
double damping_ratio(double k, double c, double m) { return c / (2.0 * std::sqrt(k) * std::sqrt(m)); }

// erp as 1 / (1 + c / (h k)): h k / (h k + c) was inf / inf, NaN, for a step of 1e308 s.
OdeErpCfm to_ode(double k, double c, double h) { return {1.0 / (1.0 + c / (h * k)), 1.0 / (h * k + c)}; }

void from_ode(const OdeErpCfm& p, double h, double& k, double& c) {
  k = p.erp / (h * p.cfm);
  c = (1.0 - p.erp) / p.cfm;
}

MujocoSolref to_mujoco(double k, double c, double m) {
  return {c > 0 ? 2.0 * m / c : std::numeric_limits<double>::infinity(), damping_ratio(k, c, m)};
}

void from_mujoco(const MujocoSolref& p, double m, double& k, double& c) {
  // b = 2 / timeconst and k/m = 1 / (timeconst^2 dampratio^2) with d = dmax = 1.
  c = std::isinf(p.timeconst) ? 0.0 : m * 2.0 / p.timeconst;
  k = std::isinf(p.timeconst) ? std::numeric_limits<double>::quiet_NaN()
                              : m / (p.timeconst * p.timeconst * p.dampratio * p.dampratio);
}

MujocoDirect to_mujoco_direct(double k, double c, double m) { return {k / m, c / m}; }

void from_mujoco_direct(const MujocoDirect& p, double m, double& k, double& c) {
  k = p.stiffness * m;
  c = p.damping * m;
}

Box2dSoft to_box2d(double k, double c, double m) {
  return {std::sqrt(k / m) / (2.0 * std::numbers::pi), damping_ratio(k, c, m)};
}

void from_box2d(const Box2dSoft& p, double m, double& k, double& c) {
  const double omega = 2.0 * std::numbers::pi * p.hertz;
  k = m * omega * omega;
  c = 2.0 * m * p.damping_ratio * omega;
}

DrakeContact to_drake(double k, double m, double g) {
  const double allowance = m * g / k;
  return {allowance, 1.0 / (std::sqrt(k / m) * allowance)};
}

double drake_stiffness(double penetration_allowance, double m, double g) {
  return m * g / penetration_allowance;
}

}  // namespace contact
