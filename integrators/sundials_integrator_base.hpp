#pragma once
// What CVODE, ERKStep and ARKStep share behind the Integrator interface: the callback data, the
// context, the state vector and linear system, statistics summed across re-initialisations, root
// directions re-applied after each one, and failures turned into SolverFailure. A concrete
// integrator supplies only its own SUNDIALS calls.
#include "contact_ode/integrators/integrator.hpp"
#include "sundials_callbacks.hpp"
#include "sundials_handles.hpp"
#include "sundials_linear_solver.hpp"
#include "sundials_vector_ops.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace contact::sundials {

class IntegratorBase : public Integrator {
 public:
  Outcome advance(double t_out) override {
    Outcome out;
    data_.clear();
    const bool starting = !(current_time() > t_);  // no step past t_ yet: (re)started there
    if (starting) start_y_ = y();
    if (failure_at_last_return_) returned_y_ = y();
    int flag = evolve(t_out, out.t);
    counters_stale_ = false;
    if (flag < 0 && data_.root_held_zero) {
      // A root function that is zero at the root just returned and still zero a little later
      // (the gap rate of two bodies moving exactly together: found in the 16-ball stack under
      // difference-quotient Jacobians) stops CVODE's check after a root.
      // Restarted there, the solver sets such a function aside until it leaves zero, as it does
      // at any initial time; the state is the root's, which the failed call left untouched.
      reinit(t_, y());
      data_.clear();
      flag = evolve(t_out, out.t);
      counters_stale_ = false;
    }
    if (flag < 0) throw failure(flag);
    // A return at a time the solver never reached. CVODE and ARKODE start (and restart) with the
    // step sqrt(hlb hub), which underflows to 0 at extreme scales (a 1e217 N/m Kelvin–Voigt
    // contact, 1e-108 s long: its dashpot's power against the absolute tolerance made hub 1e-227,
    // hlb 3e-122); the solver then stepped by 0 and returned t_out, with the state of the start, as
    // a success (the ball held at the floor). Restarted from there with the estimate's lower bound
    // hlb = 100 u max(|t|, |t_out|) as its first step, it runs (the error test grows the step).
    if (starting && out.t > t_ && !(current_time() > t_)) {
      check(set_initial_step(100 * std::numeric_limits<double>::epsilon() *
                             std::max(std::abs(t_), std::abs(t_out))),
            "setting the initial step");
      reinit(t_, start_y_);
      data_.clear();
      flag = evolve(t_out, out.t);
      counters_stale_ = false;
      check(set_initial_step(0.0),
            "setting the initial step");  // the solver's own estimate at later restarts
      if (flag < 0) throw failure(flag);
      if (out.t > t_ && !(current_time() > t_))
        throw SolverFailure(
            Status::NoProgress, t_,
            fmt::format("the solver returned t = {:.6g} s without a step from t = {:.6g} s, its "
                        "first step 0 even when set",
                        out.t, t_));
    }
    t_ = out.t;
    if (flag == kRootReturn) {
      out.root = true;
      out.roots_found.assign(data_.sys.root_count, 0);
      root_info(out.roots_found.data());
    }
    return out;
  }

  // The solver's failure `flag` as a SolverFailure with its name and message, at the time of the
  // state the integrator is left with.
  SolverFailure failure(int flag) {
    double t_reached = current_time();
    if (failure_at_last_return_ && flag != kTooMuchWork) {
      t_reached = t_;
      data_.map(y_.get()) = returned_y_;
    }
    char* name = flag_name(flag);
    SolverFailure f = data_.failure(flag, name ? name : "SUNDIALS error", t_reached);
    std::free(name);
    return f;
  }

  void reinit(double t, ConstVectorRef y) override {
    closed_ += segment_stats();  // re-initialising zeroes the solver's counters
    closed_.restarts += 1;
    counters_stale_ = true;
    data_.map(y_.get()) = y;
    t_ = t;
    check(restart(t), "re-initialisation");
    if (!directions_.empty()) set_root_directions(directions_);
  }

  void set_root_directions(const std::vector<int>& d) override {
    directions_ = d;
    check(root_directions(directions_.data()), "setting root directions");
  }
  double t() const override { return t_; }
  Eigen::Ref<const Vector> y() const override { return data_.map(y_.get()); }
  SolverStats stats() const override {
    SolverStats s = closed_;
    if (!counters_stale_) s += segment_stats();
    s.rhs_evals += preconditioner_rhs_evals();  // counted over the whole run (see below)
    return s;
  }

 protected:
  // CV_ROOT_RETURN == ARK_ROOT_RETURN == 2; CV_TOO_MUCH_WORK == ARK_TOO_MUCH_WORK == -1.
  static constexpr int kRootReturn = 2;
  static constexpr int kTooMuchWork = -1;

  IntegratorBase(OdeSystem system, double t0, ConstVectorRef y0) : t_(t0) {
    data_.sys = std::move(system);
    y_.reset(N_VNew_Serial(static_cast<sunindextype>(data_.sys.size), ctx_.get()));
    if (!y_) throw SolverFailure(Status::SolverError, t0, "N_VNew_Serial failed");
    use_compiled_vector_ops(y_.get());  // before the solver clones it
    data_.map(y_.get()) = y0;
  }
  void check(int flag, const char* call) const {
    if (flag < 0) throw SolverFailure(Status::SolverError, t_, fmt::format("{} failed ({})", call, flag));
  }
  // The analytic Jacobian's pattern (for sparse storage) and the linear system of the options.
  void make_linear_system(const IntegratorOptions& o, const OdeSystem::Jacobian& jac, ConstVectorRef y0) {
    if (o.linear_solver == LinearSolverKind::Klu && !jac)
      throw std::invalid_argument(
          "--linear-solver: value 'klu' needs an analytic Jacobian, and this system provides none; "
          "accepted for it: dense, band, gmres, gmres-band");
    if (o.jacobian == JacobianMode::Analytic && jac) jac(t_, y0, data_.J);
    const LinearSolverKind kind = o.linear_solver != LinearSolverKind::Auto ? o.linear_solver
                                  : has_narrow_band(data_.sys)              ? LinearSolverKind::Band
                                                                            : LinearSolverKind::Dense;
    linear_ = sundials::make_linear_system(kind, y_.get(), band_or_full(data_.sys),
                                           static_cast<long>(data_.J.nonZeros()), ctx_.get());
  }

  virtual int evolve(double t_out, double& t_ret) = 0;
  virtual int root_info(int* found) = 0;
  virtual int restart(double t) = 0;
  virtual int set_initial_step(double h) = 0;  // 0: the solver's own estimate
  virtual int root_directions(int* d) = 0;
  virtual double current_time() const = 0;
  virtual char* flag_name(int flag) const = 0;  // malloc'd by SUNDIALS; freed here
  virtual SolverStats segment_stats() const = 0;
  // The right-hand sides of SUNDIALS' band preconditioner (its difference-quotient Jacobians). Its
  // counter runs over the whole run: a re-initialisation does not zero it as it does the solver's.
  virtual long preconditioner_rhs_evals() const { return 0; }

  CallbackData data_;  // first member: the solver's callbacks point into it
  Context ctx_ = make_context();
  NVector y_;
  LinearSystem linear_;
  std::vector<int> directions_;
  SolverStats closed_;
  // After a re-initialisation the linear solver's counters (difference-quotient rhs, Jacobians,
  // iterations) still hold the closed segment's until the next step's setup zeroes them: the
  // segment counts nothing until the solver is called again.
  bool counters_stale_ = false;
  Vector start_y_;  // the state at t_ while the solver has taken no step past it (advance())
  // A failed step leaves CVODE at the last step it completed, its time and state. ARKODE returns
  // that step's state but leaves its time at the stage where the failed step stopped, up to a
  // step further, and tells no other (a fixed-step ARKStep run asked for 0.0116 s failed 'at
  // 0.019 s', a stage of its first step, with the state of t = 0; an adaptive IMEX run 'at 3.4 s'
  // with the state of 0.495 s). Set for ARKODE: a failure is reported at the last time it
  // returned, with that time's state (returned_y_), except when it ran out of steps, which it
  // checks between steps, where its time is that of the last step completed.
  bool failure_at_last_return_ = false;
  Vector returned_y_;
  double t_;
};

}  // namespace contact::sundials
