#pragma once
// Closed-form references for the ball drop.
//
// Rigid bounces (Newton's law v+ = -e v-). A ball released at height h0 with vertical velocity
// v0 under gravity g reaches the floor with speed V = sqrt(v0^2 + 2 g h0) at
//   T1 = (v0 + V) / g = 2 h0 / (V - v0)   (the second where v0 < 0: the first cancels),
// and after the n-th impact leaves with speed e^n V, so
//   T(n+1) = T(n) + 2 e^n V / g,     apex n:  h_n = (e^n V)^2 / (2g)  (= e^{2n} h0 when v0 = 0),
// and the impacts accumulate at the Zeno time  t_inf = T1 + 2 e V / (g (1 - e)).
// With v0 = 0: T1 = t0 = sqrt(2 h0/g), T(n+1) = T(n) + 2 e^n t0, t_inf = t0 (1+e)/(1-e).
//
// Linear spring contact (Hooke, F = k delta) entered at speed V under gravity g. With
// w = sqrt(k/m) and the static deflection s = g / w^2, the overlap obeys delta'' + w^2 delta = g:
//   delta(t) = s (1 - cos wt) + (V/w) sin wt = s + R sin(wt - phi),
//   R = sqrt(s^2 + (V/w)^2),  tan phi = s w / V = g / (w V).
// It is largest when sin(wt - phi) = 1 and returns to zero at wt - phi = pi + phi:
//   max penetration  delta_max = s + R = g/w^2 + sqrt(g^2/w^4 + V^2/w^2),
//   contact duration T_c = (pi + 2 atan(g / (w V))) / w,
// and by energy conservation the ball leaves at speed V. Without gravity these are v0 sqrt(m/k)
// and pi sqrt(m/k).
//
// Kelvin–Voigt contact (unclamped, F = k delta + c delta_dot), no gravity, zeta = c/(2 sqrt(km)) < 1,
// w_d = w sqrt(1 - zeta^2):  delta(t) = (V/w_d) exp(-zeta w t) sin(w_d t), so
//   restitution e = exp(-zeta pi / sqrt(1 - zeta^2)),  duration pi / w_d,
//   max penetration at t_m = atan2(sqrt(1 - zeta^2), zeta) / w_d:  delta_max = (V/w_d) exp(-zeta w t_m)
//   sin(w_d t_m).
//
// Clamped Kelvin–Voigt (F = max(0, k delta + c delta_dot)), no gravity: the same motion until the
// force reaches zero, k delta + c delta_dot = 0, i.e. with theta = w_d t and zeta = sin(a),
//   tan(theta) = -2 zeta sqrt(1-zeta^2) / (1 - 2 zeta^2) = -tan(2a)  =>  theta* = pi - 2 asin(zeta).
// There delta_dot = V exp(-zeta theta*/sqrt(1-zeta^2)) (cos theta* - zeta/sqrt(1-zeta^2) sin theta*)
// and the bracket is -(cos 2a + 2 sin^2 a) = -1, so the ball leaves force-free at
//   e_clamped = exp(-zeta (pi - 2 asin zeta) / sqrt(1 - zeta^2)) = e_target exp(2 zeta asin(zeta) / sqrt(1 -
//   zeta^2)),
// always above the target the damping was tuned for (e.g. 0.8 -> 0.808, 0.5 -> 0.550, 0.1 -> 0.253).
// The bodies still overlap there, by delta_r = (V/w_d) e_c exp(...) sin(theta*) = 2 zeta V e_c / w
// (sin theta* = 2 zeta sqrt(1-zeta^2)), and the contact, which lasts until the overlap closes, ends
// delta_r / (V e_c) = 2 zeta / w later: duration ((pi - 2 asin zeta) / sqrt(1-zeta^2) + 2 zeta) / w.
// Under gravity the ball is still slowed on the way out, so the speed where the overlap closes,
// not the speed at release, is the restitution the next apex and the energy agree with.
//
// Power-law contact F = K delta^n (Hertz: n = 3/2), undamped, no gravity, entered at speed V:
// energy gives V^2 - delta_dot^2 = 2K delta^(n+1) / ((n+1) m), so
//   delta_max = ((n+1) m V^2 / (2K))^(1/(n+1)),
//   T_c = 2 int_0^dmax d(delta)/delta_dot = (2 delta_max / V) int_0^1 (1 - x^(n+1))^(-1/2) dx
//       = (2 delta_max / V) B(1/(n+1), 1/2) / (n+1)
// (n = 1: pi sqrt(m/K); n = 3/2: 2.9432 delta_max / V, Hertz's classical result).
//
// Hunt–Crossley damping F = K delta^n (1 + chi delta_dot) at small chi: the loss is, to first
// order, the undamped path's integral of K chi delta^n delta_dot^2, twice the approach:
//   2 K chi delta_max^(n+1) V int_0^1 x^n sqrt(1 - x^(n+1)) dx = (2/3) m chi V^3,
// the same for every n, so 1 - e^2 = (4/3) chi V + O((chi V)^2). Lankarani–Nikravesh's rule is
// exactly this; Hunt–Crossley's agrees to first order in (1 - e); Flores' and Gonthier's, built
// for low restitution, do not.
#include <cstddef>
#include <string>

namespace contact {

struct RigidBounces {
  double g, e, V, T1;  // gravity, restitution, first impact speed, first impact time
  RigidBounces(double h0, double v0, double g, double e);
  // n = 1, 2, ...: n = 0 is refused (std::invalid_argument).
  double impact_time(std::size_t n) const;
  double apex_height(std::size_t n) const;  // after the n-th impact
  double apex_time(std::size_t n) const;
  double zeno_time() const;  // +inf for e = 1
};

struct SpringContact {
  double duration;         // [s]
  double max_penetration;  // [m]
  double exit_speed;       // [m/s]
};

// Hooke spring of stiffness k on mass m, entered at speed V > 0, under gravity g >= 0.
SpringContact hooke_contact(double m, double k, double V, double g);
// Kelvin–Voigt spring and dashpot of damping ratio zeta <= 1 on mass m, entered at speed V under
// gravity g >= 0, exactly: the penetration is a damped oscillation about the static sag g / w^2,
// its deepest point and exit speed in closed form, its end (where the overlap closes) the one zero
// of a monotone stretch, found by bisection to the doubles' resolution. Where the spring holds the
// ball for good (the oscillation never returns to zero overlap: soft springs, heavy damping) the
// duration is +inf and the exit speed 0. Without gravity: duration pi / w_d, restitution
// exp(-zeta pi / sqrt(1 - zeta^2)).
SpringContact kelvin_voigt_contact(double m, double k, double zeta, double V, double g = 0.0);
// The same law clamped to a force >= 0: as above to the deepest point (the clamp acts only after
// it), then the force falls to zero while the ball still overlaps and it flies freely (under
// gravity) until the overlap closes: duration and exit speed at that point. NaN duration and exit
// speed where the clamp takes hold again before the overlap closes (gravity's share g / (w V) of
// order one or more); +inf and 0 where the spring never lets go. Without gravity: the push
// (pi - 2 asin zeta) / w_d plus 2 zeta / w of free flight, exit speed
// clamped_kelvin_voigt_restitution(zeta) V.
SpringContact clamped_kelvin_voigt_contact(double m, double k, double zeta, double V, double g = 0.0);
// Restitution achieved by the clamped law with damping ratio zeta <= 1, no gravity (e^-2 at 1).
double clamped_kelvin_voigt_restitution(double zeta);
// Undamped power-law contact: duration, maximum penetration, exit speed V.
SpringContact power_law_contact(double m, double K, double n, double V);
// The first contact of a linear law of the registry, tuned to restitution e (its gravity-free
// value), entered at speed V under gravity g, exactly: "hooke" (hooke_contact), "kelvin-voigt"
// (kelvin_voigt_contact), "kelvin-voigt-clamped" (clamped_kelvin_voigt_contact). NaN for every
// other law. At e = 0 (critical damping) the unclamped contact never ends (duration +inf, exit speed
// 0) and the clamped one lets go at 2 / w and leaves at e^-2 V, 4 / w after it began (no gravity).
SpringContact linear_law_first_contact(const std::string& law, double m, double k, double e, double V,
                                       double g);
// B(1/(n+1), 1/2)/(n+1): the power-law contact time is 2 delta_max / V times this.
double power_law_time_factor(double n);
// Small-damping restitution loss 1 - e^2 of a Hunt–Crossley contact: (4/3) chi V.
double hunt_crossley_small_damping_loss(double chi, double V);

// Hunt–Crossley restitution, exact: hunt_crossley_restitution (models/contact_law.hpp).
// Hunt–Crossley maximum penetration, exact (no gravity): the same first integral over the approach,
// u from V to 0, gives K delta_max^(n+1) / (n+1) = m (a - ln(1 + a)) / chi^2 with a = chi V, i.e.
// the undamped m V^2 / 2 times 2 (a - ln(1 + a)) / a^2, which damping lowers from 1 (a = 0).
double hunt_crossley_max_penetration(double m, double K, double n, double chi, double V);
// The factor (a - ln(1 + a)) / a^2 above: 1/2 at a = 0, falling as a grows.
double hunt_crossley_approach_factor(double a);

// Undamped penalty bounce sequence of the ball drop under Hooke (the exact penalty solution):
// every contact lasts T_c and returns the impact speed, so T(n) = T1 + (n-1)(T_c + 2V/g).
double hooke_impact_time(double m, double k, double h0, double v0, double g, std::size_t n);

// The exact penalty solution itself: height x and velocity v of the ball at time t >= 0. Flight
// is a parabola; in contact x'' = -(k/m) x - g from x = 0, v = -V, i.e.
// x = -g/w^2 + (g/w^2) cos(w tau) - (V/w) sin(w tau); the cycle repeats every T_c + 2V/g.
struct BallState {
  double x, v;
};
BallState hooke_ball_state(double m, double k, double h0, double v0, double g, double t);
// The rigid (impulse) solution with restitution e at time t: parabolas between the impacts
// T(n), each leaving the floor at e^n V. For e < 1 the ball rests on the floor after t_inf.
BallState rigid_ball_state(double h0, double v0, double g, double e, double t);

}  // namespace contact
