#include "stepping_integrator.hpp"

#include "contact_ode/integrators/gsl_handles.hpp"

#include <fmt/format.h>
#include <gsl/gsl_errno.h>

#include <cmath>
#include <limits>

namespace contact {

SteppingIntegrator::SteppingIntegrator(OdeSystem system, double t0, ConstVectorRef y0, long max_steps)
    : sys_(std::move(system)), ta_(t0), tb_(t0), ya_(y0), yb_(y0), t_(t0), y_(y0), max_steps_(max_steps) {
  gsl::report_errors_by_return_code();
  g_.resize(static_cast<Eigen::Index>(sys_.root_count));
  g_hi_ = g_;
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
  restarted();
}

SteppingIntegrator::Outcome SteppingIntegrator::advance(double t_out) {
  Outcome out;
  long steps = 0;
  while (true) {
    if (t_ < tb_) {
      // Consume the current step up to t_out.
      const double hi = std::min(tb_, t_out);
      Vector y_hi(yb_.size());
      if (hi == tb_)
        y_hi = yb_;
      else
        dense(hi, y_hi);
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
    ta_ = tb_;
    ya_ = yb_;
    step(t_out);
    ++counts_.steps;
    if (!yb_.allFinite())
      throw SolverFailure(
          Status::NonFiniteState, ta_,
          fmt::format("state is not finite after the step from t = {:.17g} to {:.17g}", ta_, tb_));
  }
}

namespace {

struct RootProblem {
  std::function<double(double)> g;
};

double call_root_problem(double t, void* p) { return static_cast<RootProblem*>(p)->g(t); }

// +1 if g rose through zero (or reached it) from a negative value, -1 if it fell, else 0.
int crossing(double g_lo, double g_hi) {
  if (g_lo < 0 && g_hi >= 0) return 1;
  if (g_lo > 0 && g_hi <= 0) return -1;
  return 0;
}

}  // namespace

bool SteppingIntegrator::locate_root(double t_hi, ConstVectorRef y_hi, Outcome& out) {
  eval_roots(t_hi, y_hi, g_hi_);
  const std::size_t n = sys_.root_count;
  auto allowed = [&](std::size_t i, int dir) {
    return dir != 0 && (directions_.empty() || directions_[i] == 0 || directions_[i] == dir);
  };
  double t_root = std::numeric_limits<double>::infinity();
  Vector y(y_.size()), g(static_cast<Eigen::Index>(n));
  gsl::RootSolver brent(gsl_root_fsolver_alloc(gsl_root_fsolver_brent));
  if (!brent) throw SolverFailure(Status::SolverError, t_, "gsl_root_fsolver_alloc failed");
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    if (!allowed(i, crossing(g_[k], g_hi_[k]))) continue;
    RootProblem problem{[&, k](double t) {
      dense(t, y);
      eval_roots(t, y, g);
      return g[k];
    }};
    gsl_function fn{call_root_problem, &problem};
    double lo = t_, hi = t_hi;
    if (gsl_root_fsolver_set(brent.get(), &fn, lo, hi) != GSL_SUCCESS) continue;
    for (int iter = 0; iter < 200; ++iter) {
      gsl_root_fsolver_iterate(brent.get());
      lo = gsl_root_fsolver_x_lower(brent.get());
      hi = gsl_root_fsolver_x_upper(brent.get());
      // Stop at ~100 ulps of t, CVODE's own root tolerance.
      if (gsl_root_test_interval(lo, hi, 0.0, 100 * std::numeric_limits<double>::epsilon()) == GSL_SUCCESS)
        break;
    }
    t_root = std::min(t_root, hi);  // the bracket's upper end: g already has its new sign there
  }
  if (!std::isfinite(t_root)) return false;
  dense(t_root, y);
  eval_roots(t_root, y, g);
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

}  // namespace contact
