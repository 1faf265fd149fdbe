#include "stepping_integrator.hpp"

#include "contact_ode/integrators/gsl_handles.hpp"
#include "sign_change.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace contact {

namespace {

// +1 if g rose through zero (or reached it) from a negative value, -1 if it fell, else 0.
int crossing(double g_lo, double g_hi) {
  if (g_lo < 0 && g_hi >= 0) return 1;
  if (g_lo > 0 && g_hi <= 0) return -1;
  return 0;
}

}  // namespace

SteppingIntegrator::SteppingIntegrator(OdeSystem system, double t0, ConstVectorRef y0, long max_steps)
    : sys_(std::move(system)), ta_(t0), tb_(t0), ya_(y0), yb_(y0), t_(t0), y_(y0), max_steps_(max_steps) {
  gsl::report_errors_by_return_code();
  g_.resize(static_cast<Eigen::Index>(sys_.root_count));
  g_hi_ = g_;
  f_a_.resize(y0.size());
  f_b_.resize(y0.size());
  if (sys_.root_count > 0) eval_roots(t0, y0, g_);
}

void SteppingIntegrator::eval_roots(double t, ConstVectorRef y, Vector& g) {
  ++counts_.root_evals;
  sys_.roots(t, y, g);
}

void SteppingIntegrator::reinit(double t, ConstVectorRef y) {
  ta_ = tb_ = t_ = t;
  ya_ = yb_ = y_ = y;
  if (sys_.root_count > 0) eval_roots(t, y, g_);
  counts_.restarts += 1;
  trial_count_ = 0;
  have_start_slope_ = have_end_slope_ = false;
  restarted();
}

SteppingIntegrator::Outcome SteppingIntegrator::advance(double t_out) {
  Outcome out;
  long steps = 0;
  while (true) {
    if (t_ < tb_) {
      // Consume the current step up to t_out.
      double hi = std::min(tb_, t_out);  // (an inner scan may move it back)
      Vector y_hi(yb_.size());
      if (hi == tb_)
        y_hi = yb_;
      else
        dense(hi, y_hi);
      if (sys_.root_count > 0 && root_scan_parts() > 1) scan_for_crossing(hi, y_hi);
      if (sys_.root_count > 0 && locate_root(hi, y_hi, out)) return out;
      t_ = hi;
      y_ = y_hi;
      if (sys_.root_count > 0) g_.swap(g_hi_);
      if (t_ >= t_out) {
        out.t = t_;
        return out;
      }
      continue;
    }
    if (t_ >= t_out) {
      out.t = t_;
      return out;
    }
    if (++steps > max_steps_)
      throw SolverFailure(Status::MaxSteps, t_,
                          fmt::format("more than {} steps before t = {:.17g}", max_steps_, t_out));
    throw_if_stop_requested(t_);
    ta_ = tb_;
    ya_ = yb_;
    take_step(t_out);
    ++counts_.steps;
    if (sys_.root_count > 0 && steps_may_cross_twice()) shorten_until_hermite_is_faithful();
  }
}

void SteppingIntegrator::take_step(double t_limit) {
  step(t_limit);
  trial_count_ = 0;
  have_start_slope_ = have_end_slope_ = false;
  if (!yb_.allFinite())
    throw SolverFailure(
        Status::NonFiniteState, ta_,
        fmt::format("state is not finite after the step from t = {:.17g} to {:.17g}", ta_, tb_));
}

void SteppingIntegrator::shorten_until_hermite_is_faithful() {
  // A step whose cubic Hermite misses its own dense output at the midpoint by more than 1 % (of
  // each component's size over the step, or of the method's absolute tolerance) spans too much of an
  // oscillation for a root function's signs at its ends to tell whether it crossed zero: retake it to its
  // midpoint until it does. A half-period of a contact's oscillation has a Hermite error of order one,
  // a 1.4-radian step one of 1 %. Forty halvings leave 1e-12 of the step: the bound on the work.
  Vector y_mid(yb_.size()), y_herm(yb_.size());
  for (int halvings = 0; halvings < 40; ++halvings) {
    const double mid = 0.5 * (ta_ + tb_);
    hermite(mid, y_herm);
    dense(mid, y_mid);
    const Vector scale = ya_.cwiseAbs().cwiseMax(yb_.cwiseAbs()).cwiseMax(y_mid.cwiseAbs());
    if (((y_mid - y_herm).cwiseAbs().array() <= 1e-2 * scale.array() + negligible_size()).all()) return;
    step_shortened(mid - ta_);
    restarted();     // the method's memory (GSL's evolve keeps the last step's end slope) is stale
    take_step(mid);  // retaken under the method's error control (dense() is a bare re-step)
  }
}

namespace {

// The cubic through (a, ya) and (b, yb) with slopes fa and fb there, at t.
void cubic_hermite(double a, const Vector& ya, const Vector& fa, double b, const Vector& yb, const Vector& fb,
                   double t, VectorRef y) {
  const double H = b - a, s = (t - a) / H;
  const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
  const double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
  y = h00 * ya + h10 * H * fa + h01 * yb + h11 * H * fb;
}

// The quintic through (a, ya, fa), (m, ym, fm), (b, yb, fb) with those values and slopes:
// Newton's divided differences on the doubled nodes a, a, m, m, b, b. Its error at t is
// ~ (t - a)^2 (t - m)^2 (t - b)^2 y^(6) / 720, so near m far below the cubic Hermite's.
class QuinticHermite {
 public:
  QuinticHermite(double a, const Vector& ya, const Vector& fa, double m, const Vector& ym, const Vector& fm,
                 double b, const Vector& yb, const Vector& fb)
      : z_{a, a, m, m, b, b} {
    std::array<Vector, 5> d{fa, (ym - ya) / (m - a), fm, (yb - ym) / (b - m), fb};
    c_[0] = ya;
    c_[1] = d[0];
    for (std::size_t order = 2; order <= 5; ++order) {
      for (std::size_t i = 0; i + order <= 5; ++i) d[i] = (d[i + 1] - d[i]) / (z_[i + order] - z_[i]);
      c_[order] = d[0];
    }
  }
  void operator()(double t, VectorRef y) const {
    y = c_[5];
    for (std::size_t k = 5; k-- > 0;) y = y * (t - z_[k]) + c_[k];
  }

 private:
  std::array<double, 6> z_;
  std::array<Vector, 6> c_;
};

}  // namespace

const Vector& SteppingIntegrator::start_slope() {
  if (!have_start_slope_) f(ta_, ya_, f_a_);
  have_start_slope_ = true;
  return f_a_;
}

const Vector& SteppingIntegrator::end_slope() {
  if (!have_end_slope_) f(tb_, yb_, f_b_);
  have_end_slope_ = true;
  return f_b_;
}

void SteppingIntegrator::hermite(double t, VectorRef y) {
  cubic_hermite(ta_, ya_, start_slope(), tb_, yb_, end_slope(), t, y);
}

bool SteppingIntegrator::allowed(std::size_t i, int dir) const {
  return dir != 0 && (directions_.empty() || directions_[i] == 0 || directions_[i] == dir);
}

void SteppingIntegrator::scan_for_crossing(double& t_hi, Vector& y_hi) {
  const int parts = root_scan_parts();
  Vector& y = y_scan_;
  Vector& g = g_scan_;
  y.resize(y_.size());
  g.resize(static_cast<Eigen::Index>(sys_.root_count));
  for (int j = 1; j < parts; ++j) {
    const double t = t_ + (t_hi - t_) * j / parts;
    if (!(t > t_ && t < t_hi)) continue;
    dense(t, y);
    eval_roots(t, y, g);
    for (std::size_t i = 0; i < sys_.root_count; ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      if (allowed(i, crossing(g_[k], g[k]))) {
        t_hi = t;
        y_hi = y;
        return;
      }
    }
  }
}

bool SteppingIntegrator::locate_root(double t_hi, ConstVectorRef y_hi, Outcome& out) {
  const std::size_t n = sys_.root_count;
  Vector y(y_.size()), g(static_cast<Eigen::Index>(n));
  // The narrowing's work space: the scan's, which is done with them by now (no allocation per root).
  Vector& y_work = y_scan_;
  Vector& g_work = g_scan_;
  y_work.resize(y_.size());
  g_work.resize(g.size());
  double t_root = narrow_earliest_root(t_hi, y_hi, y, y_work, g_work);
  if (!std::isfinite(t_root)) return false;
  eval_roots(t_root, y, g);
  // A function that crosses zero twice within [t_, t_hi] (a ball that leaves a sagging spring and
  // lands on it again within one step) has the same sign at both ends and is not narrowed. Where
  // another function's root falls between its two crossings (the flight's apex) it has changed
  // sign at that root: its first crossing is earlier. It was reported at the apex, as if the ball
  // left the spring there at rest. So the roots are narrowed again over [t_, that root] until every
  // function that changed sign there was narrowed: each pass ends before the one before it, so
  // there are at most as many passes as functions.
  auto crossed_twice = [&] {
    for (std::size_t i = 0; i < n; ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      if (allowed(i, crossing(g_[k], g[k])) && !allowed(i, crossing(g_[k], g_hi_[k]))) return true;
    }
    return false;
  };
  for (std::size_t pass = 0; pass < n && crossed_twice(); ++pass) {
    const double t_end = t_root;
    const Vector y_end = y;
    // (Some function changed sign over [t_, t_end]; were none found, y is left at y_end.)
    t_root = std::min(t_end, narrow_earliest_root(t_end, y_end, y, y_work, g_work));
    eval_roots(t_root, y, g);
    if (!(t_root < t_end)) break;
  }
  out = Outcome{t_root, true, std::vector<int>(n, 0)};
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    const int dir = crossing(g_[k], g[k]);
    if (allowed(i, dir)) out.roots_found[i] = dir;
  }
  t_ = t_root;
  y_ = y;
  g_ = g;
  return true;
}

void SteppingIntegrator::keep_trial(double t, ConstVectorRef y, ConstVectorRef g) {
  if (trial_count_ == trials_.size()) {
    // Bounded: at most 64 per step and 8 MB in all (a 1e5-ball chain's state is 1.6 MB).
    const auto doubles = static_cast<double>(trials_.size() + 1) * static_cast<double>(y.size() + g.size());
    if (trials_.size() >= 64 || doubles > 1 << 20) return;
    trials_.emplace_back();
  }
  Trial& trial = trials_[trial_count_++];
  trial.t = t;
  trial.y = y;
  trial.g = g;
}

SteppingIntegrator::KnownBracket SteppingIntegrator::known_bracket(Eigen::Index k, double t_hi) const {
  // The earliest kept trial in (t_, t_hi) where g_k has its new sign is the bracket's upper end;
  // every trial before it has the old sign, and the latest of those is its lower end.
  const auto new_sign = [&](double gk) { return g_[k] > 0 ? gk <= 0 : gk >= 0; };
  KnownBracket known{{t_, g_[k], t_hi, g_hi_[k]}, nullptr, nullptr};
  for (std::size_t j = 0; j < trial_count_; ++j) {
    const Trial& trial = trials_[j];
    if (trial.t > t_ && trial.t < known.b.hi && new_sign(trial.g[k])) {
      known.b.hi = trial.t;
      known.b.g_hi = trial.g[k];
      known.y_hi = &trial.y;
    }
  }
  for (std::size_t j = 0; j < trial_count_; ++j) {
    const Trial& trial = trials_[j];
    if (trial.t > known.b.lo && trial.t < known.b.hi) {
      known.b.lo = trial.t;
      known.b.g_lo = trial.g[k];
      known.y_lo = &trial.y;
    }
  }
  return known;
}

double SteppingIntegrator::narrow_earliest_root(double t_hi, ConstVectorRef y_hi, Vector& y_root, Vector& y,
                                                Vector& g) {
  eval_roots(t_hi, y_hi, g_hi_);
  const std::size_t n = sys_.root_count;
  // CVODE's root tolerance: 100 ulps of t.
  const double tol = 100 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t_), std::abs(t_hi));
  // The functions that changed sign, each with its root on the step's Hermite (when dense() costs
  // a step) and g' there: the first step on dense() is then Newton's.
  struct Crossing {
    Eigen::Index k;
    int dir;
    double guess, slope;
  };
  std::vector<Crossing> crossings;
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    const int dir = crossing(g_[k], g_hi_[k]);
    if (!allowed(i, dir)) continue;
    double guess = std::numeric_limits<double>::quiet_NaN(), slope = guess;
    if (!dense_is_interpolant()) {
      auto on_hermite = [&](double t) {
        hermite(t, y);
        eval_roots(t, y, g);
        return g[k];
      };
      const double gh_lo = on_hermite(t_), gh_hi = on_hermite(t_hi);
      if (crossing(gh_lo, gh_hi) == dir) {
        guess = narrow_sign_change(on_hermite, {t_, gh_lo, t_hi, gh_hi}, tol).hi;
        const double d = 1e-4 * (t_hi - t_);
        const double a = std::max(t_, guess - d), c = std::min(t_hi, guess + d);
        slope = (on_hermite(c) - on_hermite(a)) / (c - a);
      }
    }
    crossings.push_back({k, dir, guess, slope});
  }
  // Earliest estimate first: a function whose kept trials show no sign change before the root found
  // so far cannot be the earliest, and is left (its trials serve the step's next root).
  std::stable_sort(crossings.begin(), crossings.end(), [&](const Crossing& a, const Crossing& b) {
    return (std::isnan(a.guess) ? t_hi : a.guess) < (std::isnan(b.guess) ? t_hi : b.guess);
  });
  double t_root = std::numeric_limits<double>::infinity();
  // The state at the earliest root's bracket end, kept as the bracket narrows: the end is the last
  // re-step on the new sign's side, so the root's state needs no re-step of its own (one of the
  // 3-5 per root; bitwise the same state).
  y_root = y_hi;
  for (const auto& [k, dir, guess, slope] : crossings) {
    const KnownBracket known = known_bracket(k, t_hi);
    if (known.b.lo >= t_root) continue;
    // The bracket's ends and their states: the known ones until a re-step finds either sign,
    // and then that re-step's (narrow_sign_change moves an end only to a point it evaluated).
    double t_new_sign = known.b.hi;
    Vector y_new_sign = known.y_hi ? ConstVectorRef(*known.y_hi) : y_hi;
    Vector y_old_sign = known.y_lo ? *known.y_lo : y_;
    const auto track = [&](double t, const Vector& y_t) {
      if ((g_[k] > 0 ? g[k] : -g[k]) <= 0) {  // the new sign: t becomes the bracket's upper end
        t_new_sign = t;
        y_new_sign = y_t;
      } else {
        y_old_sign = y_t;
      }
      return g[k];
    };
    auto on_dense = [&](double t) {
      dense(t, y);
      eval_roots(t, y, g);
      if (!dense_is_interpolant()) keep_trial(t, y, g);
      return track(t, y);
    };
    // After the first re-step (at the cubic's root), the root of the quintic through that point
    // and the step's ends is the next trial, for one more rhs: inside a contact's oscillation the
    // cubic of a long RK8 step is ~1e-6 s off, and the secant needed two more re-steps from there.
    bool refined = false;
    auto refine = [&](const SignChange& b, double x) -> double {
      const double H = tb_ - ta_;
      if (refined || dense_is_interpolant() || !(x - ta_ > 1e-6 * H && tb_ - x > 1e-6 * H))
        return std::numeric_limits<double>::quiet_NaN();
      refined = true;
      const Vector y_x = y;  // on_dense left dense(x) there
      Vector f_x(y.size());
      f(x, y_x, f_x);
      const QuinticHermite quintic(ta_, ya_, start_slope(), x, y_x, f_x, tb_, yb_, end_slope());
      auto on_quintic = [&](double t) {
        quintic(t, y);
        eval_roots(t, y, g);
        return g[k];
      };
      const double q_lo = on_quintic(b.lo), q_hi = on_quintic(b.hi);
      if (crossing(q_lo, q_hi) != dir) return std::numeric_limits<double>::quiet_NaN();
      return narrow_sign_change(on_quintic, {b.lo, q_lo, b.hi, q_hi}, tol).hi;
    };
    // Where the re-step follows the flow, it narrows the bracket to 1e-5 H, and the cubic Hermite
    // between the bracket's ends finishes, for their two slopes: the cubic's own error over a width
    // w is w^4 |y''''| / 384, at most (w/H)^4 (omega H)^4 / 384 of y's swing for an oscillation of
    // frequency omega, 3e-19 at w = 1e-5 H even for a step of omega H = 10 (1.6 periods), and it
    // departs from the re-step by 1e-4 of the local error (dense_follows_the_flow). Below that
    // width a re-step samples mostly its own rounding, and the bisections it then needed took two
    // thirds of RK8PD's right-hand sides on resting_cost's column.
    const double re_step_tol = dense_follows_the_flow() ? std::max(tol, 1e-5 * (tb_ - ta_)) : tol;
    const SignChange b = known.b.hi - known.b.lo <= tol
                             ? known.b
                             : narrow_sign_change(on_dense, known.b, re_step_tol, guess, 200, slope, refine);
    double hi = b.hi;
    if (b.hi - b.lo > tol && b.hi - b.lo <= re_step_tol) {  // (wider: the narrowing ran out of trials)
      const Vector y_lo = y_old_sign, y_up = y_new_sign;
      Vector f_lo(y.size()), f_up(y.size());
      f(b.lo, y_lo, f_lo);
      f(b.hi, y_up, f_up);
      auto on_cubic = [&](double t) {
        cubic_hermite(b.lo, y_lo, f_lo, b.hi, y_up, f_up, t, y);
        eval_roots(t, y, g);
        return track(t, y);
      };
      hi = narrow_sign_change(on_cubic, b, tol).hi;
    }
    if (hi < t_root) {
      t_root = hi;
      y_root = y_new_sign;  // hi is t_new_sign
    }
  }
  return t_root;
}

}  // namespace contact
