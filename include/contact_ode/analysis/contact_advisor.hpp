#pragma once
// The stiffness advisor: from a mass, an impact speed and a requirement (target restitution plus a
// maximum penetration or a contact duration) to the contact law's parameters, the contact
// frequency, the steps game integration can take, the same contact in popular engines'
// conventions, and a check of it all by simulating the contact.
//
// Design (no gravity; derivations in references.hpp):
//   kelvin-voigt           zeta = zeta(e); with theta = atan2(s, zeta), s = sqrt(1 - zeta^2):
//                          delta_max = (V/w) exp(-zeta theta / s)  =>  w = V exp(-zeta theta/s) / delta_max,
//                          T = pi / (w s)  =>  w = pi / (T s);  k = m w^2, c = 2 zeta sqrt(k m)
//   kelvin-voigt-clamped   zeta solves e_clamped(zeta) = e (GSL Brent); delta_max as unclamped,
//                          T = (pi - 2 asin zeta) / (w s). Reaches e down to exp(-2) = 0.135.
//   hertz, hunt-crossley-linear (n = 3/2, 1): chi from the damping rule; K from the undamped
//                          power law: K = (n+1) m V^2 / (2 delta_max^(n+1)), or from T through
//                          delta_max = T V / (2 B_n); damping makes the real contact slightly
//                          shallower, which the check reports.
//   hooke                  undamped: e must be 1; k = m V^2 / delta_max^2 or m (pi/T)^2.
// Stability, from the law linearised at the maximum penetration (w = sqrt(k_lin/m), zeta):
//   explicit Euler         |1 + h lambda| <= 1  <=>  h <= 2 zeta / w (no stable step undamped)
//   semi-implicit Euler    characteristic polynomial l^2 - (2 - a - b) l + (1 - a), a = 2 zeta w h,
//                          b = (w h)^2; Jury's conditions give h w < 2 (sqrt(zeta^2 + 1) - zeta)
//   game step for an energy error eps per contact, semi-implicit Euler (the error *after* the
//                          contact; inside it the energy swings by ~wh, which is no error): in
//                          contact the scheme conserves I = v^2 + w^2 x^2 - h w^2 x v exactly
//                          (test_fixed_step), and free flight is exact. Entering at a phase s of
//                          the step, the first state in contact is x = -s h V, so
//                          I = V^2 (1 + (wh)^2 (s^2 - s)); leaving at a phase r likewise
//                          I = v_out^2 (1 + (wh)^2 (r^2 - r)). With s^2 - s in [-1/4, 0],
//                          E_out / E_in lies in [1 - (wh)^2/4, 1 / (1 - (wh)^2/4)], so the worst
//                          relative error over the phases is (wh)^2 / (4 - (wh)^2) = eps at
//                          h = 2 sqrt(eps / (1 + eps)) / w. Exact for Hooke; for other laws (a
//                          dashpot breaks the conserved I) the step is checked by a scan over 32
//                          entry phases and shrunk until it meets the budget (a dashpot's error
//                          is of first order in h); a step too small to check is refused.
#include "contact_ode/models/contact_law.hpp"
#include "contact_ode/models/engine_conventions.hpp"

#include <optional>
#include <string>
#include <vector>

namespace contact {

struct ContactRequest {
  double m = 1.0;                         // effective mass [kg]
  double v = 1.0;                         // impact speed [m/s]
  double e = 0.8;                         // target restitution
  std::optional<double> max_penetration;  // [m] (exactly one of these two, or a Hertz material)
  std::optional<double> duration;         // [s]
  std::string law = "kelvin-voigt";       // a name from law_names() (law_registry.hpp)
  // The damping rule of the Hunt–Crossley laws (hertz, hunt-crossley-linear), kDefaultDampingRule
  // (exact) when unset; the other laws have none, and validate() refuses one given with them.
  std::optional<DampingRule> rule;
  // Hertz from a material instead of a requirement: sphere radius [m], Young's modulus [Pa],
  // Poisson ratio, against a rigid flat.
  std::optional<double> radius, young, poisson;
  double energy_error = 0.01;       // per contact, for the advised game step
  double engine_step = 1.0 / 60.0;  // [s], for ODE/Bullet's ERP and CFM
  double g = 9.81;                  // [m/s^2], for Drake's penetration allowance
};

struct ContactAdvice {
  ContactLaw law;
  double k_lin, c_lin;       // linearised at the maximum penetration [N/m], [N s/m]
  double omega, zeta;        // sqrt(k_lin/m) [rad/s], c_lin / (2 sqrt(k_lin m))
  double frequency_hz;       // omega / (2 pi)
  double euler_max_dt;       // [s]; 0: no stable step
  double symplectic_max_dt;  // [s]
  double game_dt;            // semi-implicit Euler step for the energy error per contact [s]
  OdeErpCfm ode;
  MujocoSolref mujoco;
  MujocoDirect mujoco_direct;
  Box2dSoft box2d;
  DrakeContact drake;
  // The check, by simulation (contact_measurement.hpp) and by running the game step:
  double achieved_penetration, achieved_duration, achieved_restitution;
  double game_energy_error;  // after one contact, worst over 32 entry phases, at game_dt
};

// Throws std::invalid_argument naming the option, the value and the accepted range.
void validate(const ContactRequest& request);
ContactAdvice advise(const ContactRequest& request);

}  // namespace contact
