#include "sundials_callbacks.hpp"

#include "sundials_linear_solver.hpp"

#include <fmt/format.h>

#include <exception>
#include <string_view>

namespace contact::sundials {

namespace {

CallbackData& data(void* user) { return *static_cast<CallbackData*>(user); }

// Calls f and checks its output. A non-finite value is a recoverable refusal (positive return):
// a trial state of an over-long step may leave the region where the model is defined, and the
// solver then retries with a smaller step, failing only if the NaN persists.
template <class F>
int guarded(CallbackData& d, double t, Eigen::Map<Vector> out, F&& f) {
  if (stop_requested()) {  // an unrecoverable refusal ends the solver's step at once
    d.stopped = true;
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
    d.callback_error = fmt::format("right-hand side is not finite at t = {:.17g}", t);
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
  Status status = Status::SolverError;
  if (stopped)
    status = Status::Interrupted;
  else if (non_finite)
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
  return guarded(d, t, out, [&] { d.sys.rhs(t, d.map(y), out); });
}

int implicit_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto& d = data(user);
  auto out = d.map(ydot);
  return guarded(d, t, out, [&] { d.sys.implicit_rhs(t, d.map(y), out); });
}

int explicit_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto& d = data(user);
  auto out = d.map(ydot);
  return guarded(d, t, out, [&] {
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
  d.sys.roots(t, d.map(y), g);
  return 0;
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
