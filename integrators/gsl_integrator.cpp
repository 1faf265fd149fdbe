#include "gsl_integrator.hpp"

#include "contact_ode/integrators/gsl_handles.hpp"
#include "dense_limit.hpp"
#include "stepping_integrator.hpp"

#include <fmt/format.h>
#include <gsl/gsl_errno.h>

#include <cmath>
#include <stdexcept>

namespace contact {

namespace {

const gsl_odeiv2_step_type* step_type(const std::string& method) {
  if (method == "gsl-rk8pd") return gsl_odeiv2_step_rk8pd;
  if (method == "gsl-rkf45") return gsl_odeiv2_step_rkf45;
  if (method == "gsl-msbdf") return gsl_odeiv2_step_msbdf;
  if (method == "gsl-bsimp") return gsl_odeiv2_step_bsimp;
  throw std::invalid_argument(fmt::format("unknown GSL method '{}'", method));
}

class GslIntegrator final : public SteppingIntegrator {
 public:
  GslIntegrator(const IntegratorOptions& o, OdeSystem system, double t0, ConstVectorRef y0)
      : SteppingIntegrator(std::move(system), t0, y0, o.max_steps),
        type_(step_type(o.method)),
        multistep_(type_ == gsl_odeiv2_step_msbdf),
        fixed_dt_(o.dt),
        atol_(o.atol),
        rtol_(o.rtol),
        analytic_(o.jacobian == JacobianMode::Analytic && static_cast<bool>(sys_.jacobian)),
        n_(static_cast<std::size_t>(y0.size())),
        fd_(y0.size()) {
    // bsimp and msbdf each hold two dense n x n matrices (the Jacobian and the iteration matrix),
    // and a one-step method has a second stepper for dense output: 29 GB for a 15000-ball chain,
    // which overcommit would grant a matrix at a time.
    if (type_ == gsl_odeiv2_step_bsimp || multistep_)
      refuse_dense_beyond_limit(
          static_cast<double>(n_), multistep_ ? 2 : 4,
          "use a SUNDIALS integrator, whose band, klu or gmres linear solver scales with n");
    gsl_sys_ = {&GslIntegrator::function, &GslIntegrator::jacobian, n_, this};
    const double h0 = o.dt > 0 ? o.dt : 1e-6;
    driver_.reset(gsl_odeiv2_driver_alloc_y_new(&gsl_sys_, type_, h0, o.atol, o.rtol));
    if (!driver_) throw SolverFailure(Status::SolverError, t0, "gsl_odeiv2_driver_alloc_y_new failed");
    max_step_ = o.max_step;
    h_ = h0;
    if (!multistep_) {
      dense_step_.reset(gsl_odeiv2_step_alloc(type_, n_));
      if (!dense_step_) throw SolverFailure(Status::SolverError, t0, "gsl_odeiv2_step_alloc failed");
    }
  }

  SolverStats stats() const override {
    SolverStats s = SteppingIntegrator::stats();
    s.failed_steps = failed_ + static_cast<long>(driver_->e->failed_steps);
    s.jac_evals = jac_evals_;
    return s;
  }

 private:
  // A non-finite value is a refusal GSL recovers from (any status but GSL_EBADFUNC): the step is
  // retried shorter, as SUNDIALS retries after a positive return. A trial stage of an over-long
  // explicit step on a stiff contact overflows long before the error test can reject the step
  // (rk8pd on a Hertz contact at K = 4e9 ended the run at t = 0.068 s; every other code went on).
  // The run fails only if the refusals persist; it then reports a non-finite state.
  int refuse_non_finite(double t) {
    non_finite_at_ = t;
    return GSL_EDOM;
  }

  static int function(double t, const double y[], double dydt[], void* params) {
    auto& self = *static_cast<GslIntegrator*>(params);
    const auto n = static_cast<Eigen::Index>(self.n_);
    Eigen::Map<Vector> out(dydt, n);
    self.f(t, Eigen::Map<const Vector>(y, n), out);
    return out.allFinite() ? GSL_SUCCESS : self.refuse_non_finite(t);
  }

  // GSL wants df/dy row-major and df/dt; the latter by a central difference in t (zero for the
  // autonomous systems of this project, at the cost of two right-hand sides).
  static int jacobian(double t, const double y[], double* dfdy, double dfdt[], void* params) {
    auto& self = *static_cast<GslIntegrator*>(params);
    const auto n = static_cast<Eigen::Index>(self.n_);
    Eigen::Map<const Vector> ym(y, n);
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(dfdy, n, n);
    ++self.jac_evals_;
    if (self.analytic_) {
      self.sys_.jacobian(t, ym, self.J_);
      J = Matrix(self.J_);
    } else {  // forward differences, one right-hand side per column
      Vector yp = ym, f0(n);
      self.f(t, ym, f0);
      for (Eigen::Index j = 0; j < n; ++j) {
        const double h = std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, std::abs(ym[j]));
        yp[j] = ym[j] + h;
        self.f(t, yp, self.fd_);
        J.col(j) = (self.fd_ - f0) / h;
        yp[j] = ym[j];
      }
    }
    const double ht = 1e-7 * std::max(1.0, std::abs(t));
    Vector fp(n), fm(n);
    self.f(t + ht, ym, fp);
    self.f(t - ht, ym, fm);
    Eigen::Map<Vector>(dfdt, n) = (fp - fm) / (2 * ht);
    return J.allFinite() ? GSL_SUCCESS : self.refuse_non_finite(t);
  }

  // A restart at a contact switch changes the dynamics: the last step proposed (a flight's, up to
  // seconds) can be far too long for the contact (milliseconds), and GSL cuts a rejected step by
  // at most 5x, so P1's rk8pd spent four rejected trials at every impact.
  void reinit(double t, ConstVectorRef y) override {
    SteppingIntegrator::reinit(t, y);
    restart_ = true;
  }

  // The starting step of Hairer, Norsett and Wanner (Solving ODEs I, II.4), in GSL's error norm
  // (the largest scaled component), from one more right-hand side. h1: the step at which a method
  // of order p errs by 1 % of the tolerance if f changes at its rate at the start; h0: one that
  // changes y by 1 % of its size. At the start the step is the smaller of h1 and 100 h0; after a
  // restart, the last proposal if h1 does not call it too long (h0 knows nothing of the order, and
  // a contact point sits at a position near zero, which makes it tiny where an RK8 step on the
  // exact parabola of a flight can be long).
  double starting_step(bool at_restart) {
    const Vector& f0 = start_slope();
    const Vector scale = (atol_ + rtol_ * ya_.array().abs()).matrix();
    const auto norm = [&](const Vector& v) { return (v.array() / scale.array()).abs().maxCoeff(); };
    const double d0 = norm(ya_), d1 = norm(f0);
    const double h0 = d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1;
    Vector f1(f0.size());
    f(ta_ + h0, ya_ + h0 * f0, f1);
    const double d2 = norm(f1 - f0) / h0, rate = std::max(d1, d2);
    const int p = static_cast<int>(gsl_odeiv2_step_order(driver_->s));
    const double h1 = rate <= 1e-15 ? std::max(1e-6, 1e-3 * h0) : std::pow(0.01 / rate, 1.0 / (p + 1));
    return std::min(at_restart ? h_ : 100 * h0, h1);
  }

  void step(double t_limit) override {
    double t = ta_;
    yb_ = ya_;
    auto* d = driver_.get();
    if (fixed_dt_ <= 0 && (!started_ || restart_)) h_ = starting_step(started_);
    started_ = true;
    restart_ = false;
    // evolve_apply ignores the driver's hmax, so the limit is enforced here: no step beyond
    // ta + max_step, and no proposed step longer than it.
    if (max_step_ > 0) {
      t_limit = std::min(t_limit, ta_ + max_step_);
      h_ = std::min(h_, max_step_);
    }
    non_finite_at_ = std::nan("");
    const int status =
        fixed_dt_ > 0
            // No control object: at a fixed step the error test must not reject.
            ? gsl_odeiv2_evolve_apply_fixed_step(d->e, nullptr, d->s, &gsl_sys_, &t, fixed_dt_, yb_.data())
            : gsl_odeiv2_evolve_apply(d->e, d->c, d->s, &gsl_sys_, &t, t_limit, &h_, yb_.data());
    if (status != GSL_SUCCESS) {
      ++failed_;
      const bool non_finite = std::isfinite(non_finite_at_);
      throw SolverFailure(
          non_finite ? Status::NonFiniteState : Status::ErrorTestFailure, ta_,
          fmt::format("GSL {}: {} (step size {:g}){}", type_->name, gsl_strerror(status), h_,
                      non_finite ? fmt::format("; right-hand side not finite at t = {:.17g}", non_finite_at_)
                                 : std::string()));
    }
    tb_ = t;
  }

  void dense(double t, VectorRef y) override {
    const double h = t - ta_;
    if (!multistep_) {  // re-step from the step's start with a fresh stepper
      y = ya_;
      gsl_odeiv2_step_reset(dense_step_.get());
      Vector yerr(y.size());
      // The start's slope is the same for every re-step of this step: evaluated once.
      const double* slope = dense_step_->type->can_use_dydt_in ? start_slope().data() : nullptr;
      if (gsl_odeiv2_step_apply(dense_step_.get(), ta_, h, y.data(), yerr.data(), slope, nullptr,
                                &gsl_sys_) == GSL_SUCCESS)
        return;
      ++dense_fallbacks_;  // e.g. bsimp's extrapolation did not converge: y is not a solution
    }
    hermite(t, y);  // the step's cubic Hermite
  }

  bool dense_is_interpolant() const override { return multistep_; }
  bool dense_follows_the_flow() const override { return !multistep_ && fixed_dt_ <= 0; }
  bool steps_may_cross_twice() const override { return type_ == gsl_odeiv2_step_bsimp; }
  double negligible_size() const override { return atol_; }
  void step_shortened(double h) override { h_ = std::min(h_, h); }

  void restarted() override {
    failed_ += static_cast<long>(driver_->e->failed_steps);  // the reset zeroes GSL's count
    gsl_odeiv2_driver_reset(driver_.get());
  }

  const gsl_odeiv2_step_type* type_;
  bool multistep_;
  double fixed_dt_, atol_, rtol_;
  bool analytic_;
  std::size_t n_;
  gsl_odeiv2_system gsl_sys_{};
  gsl::Driver driver_;
  gsl::Step dense_step_;
  double h_ = 0, max_step_ = 0;
  bool started_ = false, restart_ = false;  // a step taken; a restart since the last one
  long failed_ = 0, jac_evals_ = 0, dense_fallbacks_ = 0;
  double non_finite_at_ = std::nan("");  // the last refused evaluation's time in this step, if any
  SparseMatrix J_;
  Vector fd_;
};

}  // namespace

std::unique_ptr<Integrator> make_gsl(const IntegratorOptions& o, OdeSystem system, double t0,
                                     ConstVectorRef y0) {
  return std::make_unique<GslIntegrator>(o, std::move(system), t0, y0);
}

}  // namespace contact
