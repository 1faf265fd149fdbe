#pragma once
// The C callbacks CVODE and ARKODE call, shared by both (their signatures coincide). Each casts
// user_data back to a CallbackData, calls the OdeSystem through Eigen maps, and turns a
// non-finite result or an exception into a refusal the solver reports, never into a NaN that
// propagates.
#include "contact_ode/integrators/ode_system.hpp"
#include "contact_ode/integrators/status.hpp"

#include <nvector/nvector_serial.h>
#include <sundials/sundials_matrix.h>

#include <string>

namespace contact::sundials {

struct CallbackData {
  OdeSystem sys;
  SparseMatrix J;               // last analytic Jacobian (for copies and J v products)
  Vector implicit_part;         // IMEX without an explicit_rhs: the implicit part, subtracted
  std::string solver_message;   // the solver's last error message
  bool root_held_zero = false;  // that error: a root function zero at the last root and just after
  std::string callback_error;   // why one of our callbacks refused
  bool non_finite = false;
  bool stopped = false;  // a right-hand side refused because a stop was requested

  Eigen::Map<Vector> map(N_Vector v) const {
    return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(sys.size)};
  }
  // Clears the refusal flags before a solver call, so only that call's refusals count.
  void clear() {
    non_finite = false;
    root_held_zero = false;
    callback_error.clear();
  }
  // The SolverFailure for a negative return flag of CVODE or ARKODE.
  SolverFailure failure(int flag, const char* flag_name, double t_reached) const;
};

int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user);
int explicit_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user);  // IMEX: rhs - implicit
int implicit_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user);
int jacobian(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector);
int implicit_jacobian(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void* user, N_Vector, N_Vector,
                      N_Vector);
// J v products (GMRES): the setup evaluates the Jacobian at the Newton iterate, jtimes multiplies.
// implicit_jtimes_setup evaluates the IMEX implicit part's, as implicit_jacobian does.
int jtimes_setup(sunrealtype t, N_Vector y, N_Vector fy, void* user);
int implicit_jtimes_setup(sunrealtype t, N_Vector y, N_Vector fy, void* user);
int jtimes(N_Vector v, N_Vector Jv, sunrealtype t, N_Vector y, N_Vector fy, void* user, N_Vector);
int roots(sunrealtype t, N_Vector y, sunrealtype* gout, void* user);
void error_handler(int code, const char* module, const char* function, char* msg, void* user);

}  // namespace contact::sundials
