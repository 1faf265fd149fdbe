#pragma once
// Normal contact laws: overlap delta >= 0 [m] and its rate delta_dot [m/s] -> normal force [N].
//
// Each law is a small value type offering
//   force(d, dd)            the force, as a smooth (polynomial) extension valid for any d, so that
//                           an integrator holding a contact "on" between two located roots
//                           integrates a smooth right-hand side;
//   dforce_ddelta(d, dd)    dF/d(delta)     for analytic Jacobians;
//   dforce_drate(d, dd)     dF/d(delta_dot);
//   switching(d, dd)        > 0 exactly while the law pushes [m]; its zeros are where the force
//                           switches on or off, located by root finding;
//   stored_energy(d)        elastic energy held in the spring [J].
#include <algorithm>
#include <cmath>
#include <string>
#include <variant>

namespace contact {

// The seed's spring: F = k delta (Hooke's law with rest length zero along the normal).
struct Hooke {
  double k = 1e5;  // stiffness [N/m]

  double force(double d, double /*dd*/) const { return k * d; }
  double dforce_ddelta(double, double) const { return k; }
  double dforce_drate(double, double) const { return 0.0; }
  double switching(double d, double) const { return d; }
  double stored_energy(double d) const { return d > 0 ? 0.5 * k * d * d : 0.0; }
};

// Spring and dashpot in parallel: F = k delta + c delta_dot.
// Unclamped, the dashpot pulls (F < 0) near the end of restitution, when delta is small and
// delta_dot < 0. Clamped (`no_pull`), the force is max(0, F): the contact lets go as soon as
// k delta + c delta_dot reaches zero, while the bodies still overlap. The clamp removes the pull
// that would have slowed the separating bodies, so the achieved restitution is *higher* than the
// unclamped target; tests and the k-sweep measure by how much.
struct KelvinVoigt {
  double k = 1e5;        // stiffness [N/m]
  double c = 0.0;        // damping [N s/m]
  bool no_pull = false;  // clamp F >= 0

  double force(double d, double dd) const { return k * d + c * dd; }
  double dforce_ddelta(double, double) const { return k; }
  double dforce_drate(double, double) const { return c; }
  // Unclamped: on while overlapping. Clamped: on while overlapping *and* pushing; the second
  // condition k d + c dd > 0 is written as d + (c/k) dd > 0 so that both are lengths.
  double switching(double d, double dd) const {
    return no_pull ? std::min(d, d + (c / k) * dd) : d;
  }
  double stored_energy(double d) const { return d > 0 ? 0.5 * k * d * d : 0.0; }
};

using ContactLaw = std::variant<Hooke, KelvinVoigt>;

// Damping ratio zeta of the unclamped linear spring-dashpot that gives restitution e on an
// isolated contact without gravity.
// Derivation: m d'' + c d' + k d = 0, d(0) = 0, d'(0) = v0 gives
//   d(t) = v0/w_d exp(-zeta w t) sin(w_d t),  w = sqrt(k/m), w_d = w sqrt(1 - zeta^2);
// the overlap closes at t = pi / w_d with d' = -v0 exp(-zeta pi / sqrt(1 - zeta^2)), so
//   e = exp(-zeta pi / sqrt(1 - zeta^2))  <=>  zeta = -ln e / sqrt(pi^2 + ln^2 e).
// e -> 0 gives zeta -> 1 (critical damping: the overlap never closes).
double damping_ratio_for_restitution(double e);

// Kelvin–Voigt law for stiffness k [N/m] on a contact of effective mass m [kg] tuned to
// restitution e: c = 2 zeta sqrt(k m).
KelvinVoigt kelvin_voigt_for_restitution(double k, double m, double e, bool no_pull);

// The law's force, partial derivatives, switching function and energy, whatever its type.
double force(const ContactLaw& law, double d, double dd);
double dforce_ddelta(const ContactLaw& law, double d, double dd);
double dforce_drate(const ContactLaw& law, double d, double dd);
double switching(const ContactLaw& law, double d, double dd);
double stored_energy(const ContactLaw& law, double d);
double stiffness(const ContactLaw& law);
std::string describe(const ContactLaw& law);

}  // namespace contact
