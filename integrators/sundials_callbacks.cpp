#include "sundials_callbacks.hpp"

#include "sundials_linear_solver.hpp"

#include <fmt/format.h>

#include <cmath>
#include <exception>
#include <string_view>

namespace contact::sundials {

namespace {

CallbackData& data(void* user) { return *static_cast<CallbackData*>(user); }

// CVODE's and ARKODE's root search sees a sign change where g_lo * g_hi < 0, a product that
// underflows to 0 once both values are below about 1.6e-162: root functions of that size crossed
// unseen (a ball dropped from 1e-165 m, gravity scaled alike, fell through the floor and the run
// succeeded without a contact; from 1e-150 m, whose root offsets are a thousandth of an atol of
// 1e-159 m, it ended 'diverged'). Values below 2^-400 are compressed into [2^-530, 2^-400),
// linearly in their exponent and keeping their sign, so that the product of any two non-zero ones
// is at least 2^-1060. The map is strictly increasing and keeps 0, so each function's roots are
// where they were, and every value from 2^-400 up is passed on bitwise.
double visible_to_the_sign_test(double g) {
  constexpr double top = -400, bottom = -1074, to = -530;  // exponents: 2^-1074 is the least double
  const double size = std::abs(g);
  if (!(size < 0x1p-400) || size == 0) return g;
  return std::copysign(std::exp2(top + (std::log2(size) - top) * ((to - top) / (bottom - top))), g);
}

// Calls f, `what` naming it, and checks its time and its output. A non-finite output is a
// recoverable refusal (positive return): a trial state of an over-long step may leave the region
// where the model is defined, and the solver then retries with a smaller step, failing only if the
// NaN persists.
template <class F>
int guarded(CallbackData& d, double t, Eigen::Map<Vector> out, const char* what, F&& f) {
  if (stop_requested()) {  // an unrecoverable refusal ends the solver's step at once
    d.stopped = true;
    return -1;
  }
  // A time that is not finite is the solver's own arithmetic overflowing: CVODE's first-step
  // estimate for an output 2.5e305 s away (t_end 5e307 s) is inf. No retry mends it, and CVODE,
  // retrying recoverable refusals at t = inf, never returned.
  if (!std::isfinite(t)) {
    d.non_finite = true;
    d.callback_error = fmt::format(
        "the solver asked for the {} at t = {}: its time overflowed; shorten the time span", what, t);
    return -1;
  }
  try {
    f();
  } catch (const std::exception& e) {
    d.callback_error = e.what();
    return -1;
  }
  if (!out.allFinite()) {
    d.non_finite = true;
    d.callback_error = fmt::format("{} not finite at t = {:.17g}", what, t);
    return 1;
  }
  return 0;
}

// d.J = jac(t, y); an exception is a refusal the solver reports, as a right-hand side's is.
int evaluate_jacobian(CallbackData& d, const OdeSystem::Jacobian& jac, double t, N_Vector y) {
  try {
    jac(t, d.map(y), d.J);
  } catch (const std::exception& e) {
    d.callback_error = e.what();
    return -1;
  }
  return 0;
}

int fill_jacobian(CallbackData& d, const OdeSystem::Jacobian& jac, double t, N_Vector y, SUNMatrix A) {
  if (const int flag = evaluate_jacobian(d, jac, t, y); flag != 0) return flag;
  if (!copy_jacobian(d.J, A)) {
    d.callback_error = "the analytic Jacobian does not fit the linear solver's matrix (band or pattern)";
    return -1;
  }
  return 0;
}

}  // namespace

SolverFailure CallbackData::failure(int flag, const char* flag_name, double t_reached) const {
  // CVODE and ARKODE share these codes: -1 too much work, -2 too much accuracy requested,
  // -3 repeated error-test failures, -4 repeated convergence failures, -6/-7 linear solver.
  // A stop ends the step by refusing a callback, which the solver reports as that callback's
  // failure ("CV_RTFUNC_FAIL: ... rootfinding routine failed in an unrecoverable manner"): its
  // text describes the refusal, not the run, so a stopped run says only that it was stopped.
  if (stopped) return stopped_failure(t_reached);
  Status status = Status::SolverError;
  if (non_finite)
    status = Status::NonFiniteState;
  else if (flag == -1)
    status = Status::MaxSteps;
  else if (flag == -2 || flag == -3)
    status = Status::ErrorTestFailure;
  else if (flag == -4 || flag == -6 || flag == -7)
    status = Status::ConvergenceFailure;
  std::string msg = flag_name;
  if (!solver_message.empty()) msg += ": " + solver_message;
  if (!callback_error.empty()) msg += " (" + callback_error + ")";
  return SolverFailure(status, t_reached, msg);
}

int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto& d = data(user);
  auto out = d.map(ydot);
  return guarded(d, t, out, "right-hand side", [&] { d.sys.rhs(t, d.map(y), out); });
}

int implicit_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto& d = data(user);
  auto out = d.map(ydot);
  return guarded(d, t, out, "right-hand side", [&] { d.sys.implicit_rhs(t, d.map(y), out); });
}

int explicit_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto& d = data(user);
  auto out = d.map(ydot);
  return guarded(d, t, out, "right-hand side", [&] {
    if (d.sys.explicit_rhs) return d.sys.explicit_rhs(t, d.map(y), out);
    d.implicit_part.resize(out.size());
    d.sys.implicit_rhs(t, d.map(y), d.implicit_part);
    d.sys.rhs(t, d.map(y), out);
    out -= d.implicit_part;
  });
}

int jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector) {
  auto& d = data(user);
  return fill_jacobian(d, d.sys.jacobian, t, y, J);
}

int implicit_jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix J, void* user, N_Vector, N_Vector,
                      N_Vector) {
  auto& d = data(user);
  return fill_jacobian(d, d.sys.implicit_jacobian, t, y, J);
}

int jtimes_setup(sunrealtype t, N_Vector y, N_Vector, void* user) {
  auto& d = data(user);
  return evaluate_jacobian(d, d.sys.jacobian, t, y);
}

int implicit_jtimes_setup(sunrealtype t, N_Vector y, N_Vector, void* user) {
  auto& d = data(user);
  return evaluate_jacobian(d, d.sys.implicit_jacobian, t, y);
}

int jtimes(N_Vector v, N_Vector Jv, sunrealtype, N_Vector, N_Vector, void* user, N_Vector) {
  multiply(data(user).J, v, Jv);
  return 0;
}

int roots(sunrealtype t, N_Vector y, sunrealtype* gout, void* user) {
  auto& d = data(user);
  Eigen::Map<Vector> g(gout, static_cast<Eigen::Index>(d.sys.root_count));
  // Guarded as a right-hand side is: any non-zero return ends the solve (root functions have no
  // retry), which a non-finite value must. Unchecked, an accepted step whose state overflowed (ARKODE's
  // explicit first step of some 1e135 s, t_end 1e300 s) gave -inf and NaN root values, and ARKODE's
  // root search, whose loop ends only when its bracket narrows, ran forever.
  return guarded(d, t, g, "root functions", [&] {
    d.sys.roots(t, d.map(y), g);
    for (double& value : g) value = visible_to_the_sign_test(value);
  });
}

void error_handler(int code, const char* module, const char* function, char* msg, void* user) {
  if (code >= 0) return;  // warnings are not failures
  data(user).solver_message = fmt::format("{}:{}: {}", module, function, msg);
  // "Root found at and very near t": CVODE's cvRcheck2 names itself, ARKODE reports it from
  // arkStopTests (ARKStep) as well as arkRootCheck2, so the message is what identifies it.
  data(user).root_held_zero =
      std::string_view(msg).find("Root found at and very near") != std::string_view::npos;
}

}  // namespace contact::sundials
