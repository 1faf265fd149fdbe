// CVODE behind the Integrator interface: BDF (orders 1-5) or Adams (1-12), Newton iteration
// with the chosen linear solver, root finding.
#include "sundials_integrator_base.hpp"
#include "sundials_integrators.hpp"

#include <cvode/cvode.h>
#include <cvode/cvode_bandpre.h>
#include <sundials/sundials_version.h>

namespace contact {

namespace {

class CvodeIntegrator final : public sundials::IntegratorBase {
 public:
  CvodeIntegrator(const IntegratorOptions& o, OdeSystem system, double t0, ConstVectorRef y0)
      : IntegratorBase(std::move(system), t0, y0) {
    mem_.reset(CVodeCreate(o.method == "cvode-adams" ? CV_ADAMS : CV_BDF, ctx_.get()));
    if (!mem_) throw SolverFailure(Status::SolverError, t0, "CVodeCreate failed");
    void* m = mem_.get();
    check(CVodeSetErrHandlerFn(m, sundials::error_handler, &data_), "CVodeSetErrHandlerFn");
    check(CVodeInit(m, sundials::rhs, t0, y_.get()), "CVodeInit");
    check(CVodeSetUserData(m, &data_), "CVodeSetUserData");
    check(CVodeSStolerances(m, o.rtol, o.atol), "CVodeSStolerances");
    check(CVodeSetMaxNumSteps(m, o.max_steps), "CVodeSetMaxNumSteps");
    if (o.max_step > 0) check(CVodeSetMaxStep(m, o.max_step), "CVodeSetMaxStep");

    make_linear_system(o, data_.sys.jacobian, y0);
    check(CVodeSetLinearSolver(m, linear_.solver.get(), linear_.matrix.get()), "CVodeSetLinearSolver");
    if (o.jacobian == JacobianMode::Analytic && data_.sys.jacobian) {
      if (linear_.matrix)
        check(CVodeSetJacFn(m, sundials::jacobian), "CVodeSetJacFn");
      else
        check(CVodeSetJacTimes(m, sundials::jtimes_setup, sundials::jtimes), "CVodeSetJacTimes");
    }
    if (o.linear_solver == LinearSolverKind::GmresBandPreconditioned) {
      const auto n = static_cast<sunindextype>(data_.sys.size);
      const Bandwidth band = band_or_full(data_.sys);
      check(CVBandPrecInit(m, n, band.upper, band.lower), "CVBandPrecInit");
      band_preconditioned_ = true;
    }
    if (data_.sys.root_count > 0) {
      check(CVodeRootInit(m, static_cast<int>(data_.sys.root_count), sundials::roots), "CVodeRootInit");
      // A ball dropped from rest starts with a zero gap rate; that is not a problem to warn about.
      check(CVodeSetNoInactiveRootWarn(m), "CVodeSetNoInactiveRootWarn");
    }
  }

 private:
  int evolve(double t_out, double& t_ret) override {
    return CVode(mem_.get(), t_out, y_.get(), &t_ret, CV_NORMAL);
  }
  int root_info(int* found) override { return CVodeGetRootInfo(mem_.get(), found); }
  int restart(double t) override { return CVodeReInit(mem_.get(), t, y_.get()); }
  int set_initial_step(double h) override { return CVodeSetInitStep(mem_.get(), h); }
  int root_directions(int* d) override { return CVodeSetRootDirection(mem_.get(), d); }
  double current_time() const override {
    double t = t_;
    CVodeGetCurrentTime(mem_.get(), &t);
    return t;
  }
  char* flag_name(int flag) const override { return CVodeGetReturnFlagName(flag); }
  SolverStats segment_stats() const override {
    SolverStats s;
    long nfe_ls = 0, netf = 0, ncfn = 0;
    void* m = mem_.get();
    CVodeGetNumSteps(m, &s.steps);
    CVodeGetNumRhsEvals(m, &s.rhs_evals);
    CVodeGetNumLinRhsEvals(m, &nfe_ls);
    CVodeGetNumErrTestFails(m, &netf);
    CVodeGetNumNonlinSolvConvFails(m, &ncfn);
    CVodeGetNumNonlinSolvIters(m, &s.newton_iters);
    CVodeGetNumJacEvals(m, &s.jac_evals);
    CVodeGetNumLinSolvSetups(m, &s.linear_setups);
    CVodeGetNumLinIters(m, &s.linear_iters);
    if (data_.sys.root_count > 0) CVodeGetNumGEvals(m, &s.root_evals);
    if (!linear_.matrix) {  // matrix-free: each J v setup evaluates the analytic Jacobian
      long njtsetup = 0;
      CVodeGetNumJTSetupEvals(m, &njtsetup);
      s.jac_evals += njtsetup;
    }
    s.rhs_evals += nfe_ls;  // difference-quotient Jacobian columns (or J v) are rhs calls too
    s.failed_steps = netf + ncfn;
    return s;
  }

  long preconditioner_rhs_evals() const override {
    long n = 0;
    if (band_preconditioned_) CVBandPrecGetNumRhsEvals(mem_.get(), &n);
    return n;
  }

  sundials::CvodeMemory mem_;
  bool band_preconditioned_ = false;
};

}  // namespace

std::unique_ptr<Integrator> make_cvode(const IntegratorOptions& o, OdeSystem system, double t0,
                                       ConstVectorRef y0) {
  return std::make_unique<CvodeIntegrator>(o, std::move(system), t0, y0);
}

std::string sundials_version() {
  char buf[64] = {};
  SUNDIALSGetVersion(buf, sizeof buf);
  return buf;
}

}  // namespace contact
