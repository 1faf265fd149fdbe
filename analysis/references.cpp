#include "contact_ode/analysis/references.hpp"

#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/contact_law.hpp"
#include "contact_ode/models/parameters.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace contact {

namespace {
// The closed forms' domains (references.hpp): outside them a formula returns NaN or a number
// that means nothing (a negative damping ratio, an apex above the drop), so they are refused.
constexpr Range kDampingRatio{.lo = 0, .hi = 1, .lo_open = false, .hi_open = false};

// A spring contact's formulas divide by w^2 = k / m and by w (the sag g / w^2, the depth V / w)
// and multiply by them; a ratio outside the doubles' normal range (k / m = 1e312 overflows, 1e-312
// is subnormal) made every number NaN, returned as an answer, so it is refused.
void require_frequency(const std::string& f, double m, double k, double g) {
  constexpr double lo = std::numeric_limits<double>::min(), hi = std::numeric_limits<double>::max();
  const double w2 = k / m;
  if (!(w2 >= lo && w2 <= hi))
    throw std::invalid_argument(
        fmt::format("{}: k / m = {} (k = {}, m = {}), the contact's frequency "
                    "squared, is out of the doubles' normal range [{}, {}]",
                    f, w2, k, m, lo, hi));
  if (!std::isfinite(g / w2))
    throw std::invalid_argument(fmt::format(
        "{}: the static sag g m / k = {} (g = {}, m = {}, k = {}) overflows", f, g / w2, g, m, k));
}

// The flights after the first impact, 2 e V / (g (1 - e)) for e < 1: the Zeno time's tail.
double zeno_tail(const RigidBounces& b) { return 2.0 * b.e * b.V / (b.g * (1.0 - b.e)); }
}  // namespace

RigidBounces::RigidBounces(double h0, double v0, double g_, double e_)
    // A ball thrown down fast under weak gravity: v0 + V cancelled (T1 = 0.0142 s for 0.01 s at
    // h0 = 1 m, v0 = -100 m/s, g = 1e-12 m/s^2), where 2 h0 / (V - v0), the same root, does not.
    : g(g_), e(e_), V(impact_speed(h0, v0, g_)), T1(v0 < 0 ? 2.0 * h0 / (V - v0) : (v0 + V) / g_) {
  require_in("rigid bounces: h0", h0, kNonNegative);
  require_in("rigid bounces: v0", v0, kAnyFinite);
  require_in("rigid bounces: g", g, kPositive);
  require_in("rigid bounces: e", e, kUnitInterval);
  // Each argument finite, their impact still may not be (g = h0 = 1.5e308: V = 2.1e308, and every
  // apex was NaN); refused, naming the three, as the ball_drop program refuses --g, --h0, --v0.
  if (!std::isfinite(V) || !std::isfinite(T1))
    throw std::invalid_argument(fmt::format(
        "rigid bounces: the first impact (speed sqrt(v0^2 + 2 g h0) = {}, time (v0 + V) / g = {}) is "
        "beyond the doubles' range for h0 = {}, v0 = {}, g = {}",
        V, T1, h0, v0, g));
}

// The impacts and apexes are counted from 1 (apex n follows impact n). n = 0 was taken for 1 by
// impact_time and gave V^2 / 2g from apex_height, so a 0-based loop in Python read the first impact
// twice: refused, naming the count.
static void require_counted_from_one(const std::string& what, std::size_t n) {
  static constexpr Range kCount{.lo = 1, .lo_open = false, .whole = true};
  require_in("rigid bounces: " + what + " n (counted from 1: apex n follows impact n)",
             static_cast<double>(n), kCount);
}

double RigidBounces::impact_time(std::size_t n) const {
  require_counted_from_one("impact time", n);
  // T(n) = T1 + (2V/g) (e + e^2 + ... + e^{n-1}) in closed form: the Zeno tail 2eV / (g (1 - e))
  // times 1 - e^{n-1}, a fraction of at most one (expm1 keeps it exact near e = 1), so T(n) never
  // passes zeno_time() by rounding, and a large n is no longer n terms (2^63 never returned).
  if (n <= 1) return T1;
  const double gaps = static_cast<double>(n - 1);
  if (e == 1.0) return T1 + gaps * (2.0 * V / g);
  return T1 + zeno_tail(*this) * -std::expm1(gaps * std::log(e));  // e = 0: log 0 = -inf, the fraction 1
}

double RigidBounces::apex_height(std::size_t n) const {
  require_counted_from_one("apex height", n);
  const double vn = std::pow(e, static_cast<double>(n)) * V;
  return vn * (vn / (2.0 * g));  // not vn^2 / 2g: vn^2 underflows for speeds below 1e-162 m/s
}

double RigidBounces::apex_time(std::size_t n) const {
  require_counted_from_one("apex time", n);
  return impact_time(n) + std::pow(e, static_cast<double>(n)) * V / g;
}

double RigidBounces::zeno_time() const {
  return e < 1 ? T1 + zeno_tail(*this) : std::numeric_limits<double>::infinity();
}

SpringContact hooke_contact(double m, double k, double V, double g) {
  require_in("hooke_contact: m", m, kPositive);
  require_in("hooke_contact: k", k, kPositive);
  require_in("hooke_contact: g", g, kNonNegative);
  require_in("hooke_contact: V", V, g > 0 ? kNonNegative : kPositive);  // no contact without either
  require_frequency("hooke_contact", m, k, g);
  const double w = std::sqrt(k / m), s = g / (w * w);
  const double R = std::hypot(s, V / w);  // s^2 overflowed for m = 1e308 (a depth of 2e305 m, given as inf)
  return {(std::numbers::pi + 2.0 * std::atan(g / (w * V))) / w, s + R, V};
}

namespace {

// c + e^(-s t) (a cos(wd t) + b sin(wd t)): a Kelvin–Voigt contact's penetration about its static
// sag c, and every linear combination of it and its derivatives (a damped wave about a constant).
// Critically damped (wd = 0, e = 0) it is c + e^(-s t) (a + b t), the limit with b standing for
// wd b: the formulas were 0 / 0 there, NaN for every quantity of a contact tuned to e = 0. (b is
// not wd b throughout: w^2 b overflowed for a contact scaled by 2^1020.) At t = +inf the wave has
// settled on c.
struct DampedWave {
  double c, a, b, s, wd;
  double operator()(double t) const {
    if (t == std::numeric_limits<double>::infinity()) return c;
    return c + std::exp(-s * t) * (wd > 0 ? a * std::cos(wd * t) + b * std::sin(wd * t) : a + b * t);
  }
  DampedWave derivative() const {
    if (!(wd > 0)) return {0.0, -s * a + b, -s * b, s, wd};
    return {0.0, -s * a + wd * b, -s * b - wd * a, s, wd};
  }
  DampedWave plus(double k, const DampedWave& o) const {
    return {c + k * o.c, a + k * o.a, b + k * o.b, s, wd};
  }
  // The first time after t at which the wave turns (its derivative's zeros are pi / wd apart; one
  // within 1e-9 of that of t, t's own by rounding, is not after it); +inf if none (critically
  // damped, it turns once at most).
  double next_turn(double t) const {
    const DampedWave d = derivative();  // d = e^(-s t) r cos(wd t - psi): zero at wd t = psi + pi/2 + j pi
    if (!(wd > 0)) {                    // d = e^(-s t) (A + B t)
      const double turn = d.b != 0 ? -d.a / d.b : std::numeric_limits<double>::infinity();
      return turn > t + 1e-9 * std::abs(turn) ? turn : std::numeric_limits<double>::infinity();
    }
    const double psi = std::atan2(d.b, d.a), period = std::numbers::pi / wd;
    double turn = (psi + std::numbers::pi / 2) / wd;
    turn += period * std::ceil((t - turn) / period);
    return turn > t + 1e-9 * period ? turn : turn + period;
  }
  // Its zero in [lo, hi], where it falls from positive to at most zero, monotonically: bisection
  // to the doubles' resolution (64 halvings at most).
  double zero_between(double lo, double hi) const {
    for (int i = 0; i < 64; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (!(mid > lo && mid < hi)) break;
      ((*this)(mid) > 0 ? lo : hi) = mid;
    }
    return hi;
  }
};

// The first contact of the Kelvin–Voigt ball: x'' = g - w^2 x - 2 zeta w x' for the penetration x,
// x(0) = 0, x'(0) = V, until x returns to 0 (the unclamped law), or until the force w^2 x + 2 zeta w x'
// falls to zero (the clamped law lets go there and the ball flies freely until the overlap closes).
struct KelvinVoigtFirstContact {
  double w, sigma, g;
  DampedWave x;
  double t_deepest, t_shallowest;  // x's first maximum, and the minimum after it

  KelvinVoigtFirstContact(double m, double k, double zeta, double V, double g_)
      : w(std::sqrt(k / m)), sigma(zeta * w), g(g_) {
    const double wd = w * std::sqrt(1.0 - zeta * zeta), sag = g / (w * w);
    const double rise = V - sigma * sag;  // x'(0) = V
    x = {sag, -sag, wd > 0 ? rise / wd : rise, sigma, wd};
    t_deepest = x.next_turn(0.0);
    t_shallowest = x.next_turn(t_deepest);
  }
  // The overlap closes before the oscillation about the sag turns back; else the spring holds the
  // ball for good (later turns are shallower still): an unending contact, left at speed 0.
  SpringContact unclamped() const {
    const double x_max = x(t_deepest);
    // (Critically damped, x settles on the sag without turning back: t_shallowest = +inf.)
    if (!std::isfinite(t_shallowest) || x(t_shallowest) > 0)
      return {std::numeric_limits<double>::infinity(), x_max, 0.0};
    const double t_end = x.zero_between(t_deepest, t_shallowest);
    return {t_end, x_max, -x.derivative()(t_end)};
  }
  // The release: the force's first zero after the deepest point (it turns at most twice before
  // x's next turn). Then free flight, x'' = g, until x = 0, provided the force stays <= 0 meanwhile
  // (w^2 x + 2 sigma x' along the flight is w^2 tau (v_r + c g + g tau / 2), c = 2 sigma / w^2);
  // where the clamp takes hold again there is no closed form (NaN), and without a release the
  // spring holds the ball as unclamped. The force is taken over w^2 (its sign is all that counts),
  // the flight's speeds over v_r: w^2 x and v_r^2 overflowed for a contact at 1e307 m/s, which
  // came out as one that never let go.
  SpringContact clamped() const {
    const double x_max = x(t_deepest), c = 2 * (sigma / w) / w;
    const DampedWave force = DampedWave{0, 0, 0, sigma, x.wd}.plus(1.0, x).plus(c, x.derivative());
    double lo = t_deepest, t_release = NAN;
    for (int piece = 0; piece < 3 && lo < t_shallowest && std::isnan(t_release); ++piece) {
      const double hi = std::min(force.next_turn(lo), t_shallowest);
      if (std::isfinite(hi) && force(hi) <= 0) t_release = force.zero_between(lo, hi);
      lo = hi;
    }
    if (std::isnan(t_release)) return {std::numeric_limits<double>::infinity(), x_max, 0.0};
    const double x_r = x(t_release), v_r = x.derivative()(t_release);
    const double q = 2 * (g / v_r) * (x_r / v_r);  // 2 g x_r / v_r^2: the exit speed is |v_r| sqrt(1 - q)
    if (!(v_r < 0 && q <= 1)) return {NAN, x_max, NAN};
    const double root = std::sqrt(1 - q), flight = 2 * (x_r / -v_r) / (1 + root);
    if (v_r + c * g + g * flight / 2 > 0) return {NAN, x_max, NAN};
    return {t_release + flight, x_max, -v_r * root};
  }
};

void require_kelvin_voigt(const char* name, double m, double k, double zeta, double V, double g) {
  const std::string f(name);
  require_in(f + ": m", m, kPositive);
  require_in(f + ": k", k, kPositive);
  require_in(f + ": zeta", zeta, kDampingRatio);  // up to critical damping (e = 0)
  require_in(f + ": g", g, kNonNegative);
  require_in(f + ": V", V, g > 0 ? kNonNegative : kPositive);  // no contact without either
  require_frequency(f, m, k, g);
}

}  // namespace

SpringContact kelvin_voigt_contact(double m, double k, double zeta, double V, double g) {
  require_kelvin_voigt("kelvin_voigt_contact", m, k, zeta, V, g);
  return KelvinVoigtFirstContact(m, k, zeta, V, g).unclamped();
}

SpringContact clamped_kelvin_voigt_contact(double m, double k, double zeta, double V, double g) {
  require_kelvin_voigt("clamped_kelvin_voigt_contact", m, k, zeta, V, g);
  return KelvinVoigtFirstContact(m, k, zeta, V, g).clamped();
}

double clamped_kelvin_voigt_restitution(double zeta) {
  if (zeta == 1) return std::exp(-2.0);  // the limit: (pi - 2 asin zeta) / sqrt(1 - zeta^2) -> 2
  return std::exp(-zeta * (std::numbers::pi - 2.0 * std::asin(zeta)) / std::sqrt(1.0 - zeta * zeta));
}

SpringContact linear_law_first_contact(const std::string& law, double m, double k, double e, double V,
                                       double g) {
  const double nan = std::nan("");
  require_in("linear_law_first_contact: m", m, kPositive);
  require_in("linear_law_first_contact: k", k, kPositive);
  require_in("linear_law_first_contact: e", e, kUnitInterval);
  require_in("linear_law_first_contact: V", V, kPositive);
  require_in("linear_law_first_contact: g", g, kNonNegative);
  if (law == "hooke") return hooke_contact(m, k, V, g);
  const bool clamped = law == "kelvin-voigt-clamped";
  if (law != "kelvin-voigt" && !clamped) return {nan, nan, nan};
  const double zeta = damping_ratio_for_restitution(e);
  return clamped ? clamped_kelvin_voigt_contact(m, k, zeta, V, g) : kelvin_voigt_contact(m, k, zeta, V, g);
}

double power_law_time_factor(double n) {
  const double a = 1.0 / (n + 1.0);
  return a * std::tgamma(a) * std::tgamma(0.5) / std::tgamma(a + 0.5);
}

SpringContact power_law_contact(double m, double K, double n, double V) {
  require_in("power_law_contact: m", m, kPositive);
  require_in("power_law_contact: K", K, kPositive);
  require_in("power_law_contact: n", n, kPositive);
  require_in("power_law_contact: V", V, kPositive);
  // ((n + 1) m V^2 / 2K)^(1 / (n + 1)) with V's power apart: V^2 underflowed to 0 for a contact at
  // 1e-165 m/s (a drop scaled by 2^-540), whose penetration and duration came out 0.
  const double dmax = std::pow(V, 2.0 / (n + 1.0)) * std::pow((n + 1.0) * m / (2.0 * K), 1.0 / (n + 1.0));
  return {2.0 * dmax / V * power_law_time_factor(n), dmax, V};
}

double hunt_crossley_small_damping_loss(double chi, double V) { return 4.0 / 3.0 * chi * V; }

double hunt_crossley_approach_factor(double a) {
  require_in("hunt_crossley_approach_factor: chi V", a, kNonNegative);
  // Small a: a - ln(1 + a) cancels to a^2 / 2, so the series 1/2 - a/3 + a^2/4 - a^3/5 (its error
  // a^4 / 6, below 2e-13 at a = 1e-3); log1p above it.
  if (a < 1e-3) return 0.5 + a * (-1.0 / 3.0 + a * (0.25 - a * 0.2));
  return (a - std::log1p(a)) / (a * a);
}

double hunt_crossley_max_penetration(double m, double K, double n, double chi, double V) {
  require_in("hunt_crossley_max_penetration: m", m, kPositive);
  require_in("hunt_crossley_max_penetration: K", K, kPositive);
  require_in("hunt_crossley_max_penetration: n", n, kPositive);
  require_in("hunt_crossley_max_penetration: chi", chi, kNonNegative);
  require_in("hunt_crossley_max_penetration: V", V, kPositive);
  return std::pow(V, 2.0 / (n + 1.0)) *  // apart, as in power_law_contact
         std::pow((n + 1.0) * m * hunt_crossley_approach_factor(chi * V) / K, 1.0 / (n + 1.0));
}

double hooke_impact_time(double m, double k, double h0, double v0, double g, std::size_t n) {
  const RigidBounces rigid(h0, v0, g, 1.0);
  const double cycle = hooke_contact(m, k, rigid.V, g).duration + 2.0 * rigid.V / g;
  return rigid.T1 + static_cast<double>(n - 1) * cycle;
}

BallState hooke_ball_state(double m, double k, double h0, double v0, double g, double t) {
  const RigidBounces rigid(h0, v0, g, 1.0);
  if (t < rigid.T1) return {h0 + v0 * t - 0.5 * g * t * t, v0 - g * t};
  const double V = rigid.V, w = std::sqrt(k / m), s = g / (w * w);
  const double tc = hooke_contact(m, k, V, g).duration;
  const double tau = std::fmod(t - rigid.T1, tc + 2.0 * V / g);
  if (tau < tc)
    return {-s + s * std::cos(w * tau) - V / w * std::sin(w * tau),
            -s * w * std::sin(w * tau) - V * std::cos(w * tau)};
  const double f = tau - tc;  // flight after leaving at speed V
  return {V * f - 0.5 * g * f * f, V - g * f};
}

BallState rigid_ball_state(double h0, double v0, double g, double e, double t) {
  const RigidBounces rigid(h0, v0, g, e);
  if (t < rigid.T1) return {h0 + v0 * t - 0.5 * g * t * t, v0 - g * t};
  if (t >= rigid.zeno_time()) return {0.0, 0.0};
  const double period = 2.0 * rigid.V / g;  // the flight after the first impact, at e = 1
  const double s = t - rigid.T1;
  // The leg n = 0, 1, ... leaves the floor at T1 + period (e + ... + e^n) with speed e^(n+1) V.
  // Leg n contains t when period e (1 - e^n) / (1 - e) <= s, i.e. n = floor(log(1 - s (1-e) /
  // (period e)) / log e), computed directly: stepping through the legs one by one never ends
  // once they are shorter than t's rounding, between the floating-point sum of the impact times
  // and t_inf.
  double n = 0.0;
  if (e == 1.0)
    n = std::floor(s / period);
  else if (e > 0.0)
    n = std::floor(std::log1p(-s * (1.0 - e) / (period * e)) / std::log(e));
  n = std::max(n, 0.0);
  const double en = std::pow(e, n);
  const double start = rigid.T1 + (e == 1.0 ? n * period : period * e * (1.0 - en) / (1.0 - e));
  double speed = en * e * rigid.V;
  // The logarithm may land one leg off where t is an impact time to rounding: move at most one
  // leg either way so that start <= t < start + 2 speed / g.
  double f = t - start;
  if (f < 0) f = 0;
  if (speed > 0 && f > 2.0 * speed / g) {
    f -= 2.0 * speed / g;
    speed *= e;
  }
  if (!(speed > 0) || f > 2.0 * speed / g) return {0.0, 0.0};  // below t's resolution of t_inf
  return {speed * f - 0.5 * g * f * f, speed - g * f};
}

}  // namespace contact
