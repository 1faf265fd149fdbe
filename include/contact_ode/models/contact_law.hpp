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
//   releases_while_overlapping()  whether the switching function can fall to zero while the
//                           overlap d is still positive (a clamped law); when not, its sign is
//                           the overlap's and the overlap's closing needs no root of its own;
//   stored_energy(d)        elastic energy held in the spring [J], the potential of its force also
//                           for d < 0: a located switch turns a spring off a little past touching
//                           (contact_threshold), where its force has pulled; a spring counted as
//                           holding nothing there left that work out of the energy ledger, half k
//                           times the threshold squared per contact;
//   dissipated_power(d, dd) power the law's damping removes while it pushes [W] (energy ledger).
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace contact {

// The seed's spring: F = k delta (Hooke's law with rest length zero along the normal).
struct Hooke {
  double k = 1e5;  // stiffness [N/m]

  double force(double d, double /*dd*/) const { return k * d; }
  double dforce_ddelta(double, double) const { return k; }
  double dforce_drate(double, double) const { return 0.0; }
  double switching(double d, double) const { return d; }
  bool releases_while_overlapping() const { return false; }
  double stored_energy(double d) const { return 0.5 * k * d * d; }
  double dissipated_power(double, double) const { return 0.0; }
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
  double switching(double d, double dd) const { return no_pull ? std::min(d, d + (c / k) * dd) : d; }
  bool releases_while_overlapping() const { return no_pull; }
  double stored_energy(double d) const { return 0.5 * k * d * d; }
  // Power the dashpot takes out while the law is on [W]: c delta_dot^2. (Unclamped, the dashpot
  // also acts at small negative delta near the end; the ledger counts it where the law is on.)
  double dissipated_power(double, double dd) const { return c * dd * dd; }
};

// The Hunt–Crossley family: F = K delta^n (1 + chi delta_dot), clamped to F >= 0 (a contact
// pushes, it never glues). n = 3/2 with chi = 0 is Hertz's law. The damping term vanishes with
// the overlap, so the force has no jump when contact begins or ends, unlike Kelvin–Voigt.
// For delta < 0 (the smooth extension integrators may probe past a located root) delta^n is
// continued as sign(delta) |delta|^n.
struct HuntCrossley {
  double k = 1e9;    // K [N/m^n]
  double n = 1.5;    // exponent
  double chi = 0.0;  // damping factor [s/m]

  double force(double d, double dd) const { return k * pow_n(d) * (1.0 + chi * dd); }
  double dforce_ddelta(double d, double dd) const {
    return k * n * std::pow(std::abs(d), n - 1.0) * (1.0 + chi * dd);
  }
  // K delta^n first, the force's scale: K chi overflowed for a heavy, slow body (K 1e300, chi 1e161).
  double dforce_drate(double d, double) const { return k * pow_n(d) * chi; }
  // On while overlapping and 1 + chi delta_dot > 0. The second factor is dimensionless; it is
  // scaled by 1 mm only to read as a length (a root's location does not depend on the scale).
  double switching(double d, double dd) const { return std::min(d, 1e-3 * (1.0 + chi * dd)); }
  bool releases_while_overlapping() const { return chi != 0.0; }
  double stored_energy(double d) const { return k * std::pow(std::abs(d), n + 1.0) / (n + 1.0); }
  double dissipated_power(double d, double dd) const { return d > 0 ? k * pow_n(d) * (chi * dd) * dd : 0.0; }

 private:
  double pow_n(double d) const { return std::copysign(std::pow(std::abs(d), n), d); }
};

using ContactLaw = std::variant<Hooke, KelvinVoigt, HuntCrossley>;

// A law's spring and dashpot when it is linear, F = k delta + c delta' (Hooke, Kelvin–Voigt, and
// Hunt–Crossley with n = 1 and no damping); NaN in both otherwise.
struct LinearLaw {
  double k;  // stiffness [N/m]
  double c;  // dashpot [N s/m]
};
LinearLaw linear_law(const ContactLaw& law);

// Hunt–Crossley restitution, exact (no gravity, no clamp acting): with u the overlap rate,
// m u du / (1 + chi u) = -K delta^n d(delta); over the whole contact delta returns to 0, so the
// right side integrates to zero and, with a = chi V and e = u_out / V,
//   a - ln(1 + a) = -a e - ln(1 - a e),
// whatever n, K and m: the restitution depends on chi V alone (1 + chi u > 0 throughout: u = -1/chi
// is where the velocity stops changing, so 1 - a e > 0 and the clamp F >= 0 never acts). Solved by
// bisection in ln(1 - a e), for every a >= 0 (e -> 1/a as a grows).
double hunt_crossley_restitution(double chi_v);
// Its inverse: the a = chi V >= 0 whose contact has restitution e in (0, 1] (0 at e = 1, about
// 1 / e as e -> 0; e = 0 would need an infinite one: +inf).
double hunt_crossley_chi_v(double e);

// Rules that set the Hunt–Crossley damping factor from a target restitution e and the impact
// speed v (> 0). The four of the literature were each derived for a particular range of e, and
// the study measures how far each misses its target elsewhere; the exact one inverts the relation
// above, so its contact has restitution e at v whatever n, K and m (without gravity):
//   Hunt & Crossley (1975)          chi = 3 (1 - e) / (2 v)
//   Lankarani & Nikravesh (1990)    chi = 3 (1 - e^2) / (4 v)        (derived for e near 1)
//   Flores et al. (2011)            chi = 8 (1 - e) / (5 e v)
//   Gonthier et al. (2004)          chi = (1 - e^2) / (e v)
//   exact                           chi = hunt_crossley_chi_v(e) / v
enum class DampingRule { HuntCrossley, LankaraniNikravesh, Flores, Gonthier, Exact };
// Every rule, in the order above (sweeps over them, the command lines' choices).
inline constexpr std::array<DampingRule, 5> kDampingRules = {
    DampingRule::HuntCrossley, DampingRule::LankaraniNikravesh, DampingRule::Flores, DampingRule::Gonthier,
    DampingRule::Exact};
// The default wherever a rule is not named: the one that meets e. Lankarani–Nikravesh's before it
// tuned a Hertz ball asked for e = 0.3 to bounce at 0.68 (ball_drop --law hertz --k 1e7).
inline constexpr DampingRule kDefaultDampingRule = DampingRule::Exact;
double damping_factor(DampingRule rule, double e, double v);
std::string_view to_string(DampingRule rule);
std::vector<std::string> damping_rule_names();  // kDampingRules' names, in order
// The rule named `name`; throws std::invalid_argument naming --rule and the accepted names.
DampingRule parse_damping_rule(const std::string& name);

// Hertz stiffness of a sphere of radius R [m] on a flat, K = (4/3) E* sqrt(R) [N/m^(3/2)], with
// the effective modulus 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (a rigid flat: E2 = infinity).
// For two spheres R is the effective radius R1 R2 / (R1 + R2).
double effective_modulus(double E1, double nu1, double E2, double nu2);
double hertz_stiffness(double radius, double effective_modulus);

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
bool releases_while_overlapping(const ContactLaw& law);
double stored_energy(const ContactLaw& law, double d);
double dissipated_power(const ContactLaw& law, double d, double dd);
double stiffness(const ContactLaw& law);
// The power of delta in the elastic force: n for Hunt–Crossley laws, 1 for the linear ones.
double exponent(const ContactLaw& law);
std::string describe(const ContactLaw& law);

}  // namespace contact
