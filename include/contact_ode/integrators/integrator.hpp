#pragma once
// One interface for every time integrator: fixed-step schemes, SUNDIALS CVODE and ARKODE, GSL
// odeiv2, and the exact solution of a system affine between its switches. Each integrates an
// OdeSystem towards an output time, stops at the first root of its root functions on the way, can
// be restarted from an edited state, and reports the same SolverStats. Paradigms (penalty,
// event-driven) drive an Integrator without knowing which.
#include "contact_ode/integrators/ode_system.hpp"
#include "contact_ode/integrators/solver_stats.hpp"
#include "contact_ode/integrators/status.hpp"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace contact {

enum class JacobianMode { Analytic, DifferenceQuotient };
// Auto (the default): band where the system's Jacobian band is narrower than the system (a chain,
// a column: has_narrow_band), dense otherwise.
enum class LinearSolverKind { Auto, Dense, Band, Klu, Gmres, GmresBandPreconditioned };

struct IntegratorOptions {
  std::string method = "cvode-bdf";  // a name from integrator_catalog()
  double rtol = 1e-8;                // relative tolerance (adaptive methods)
  double atol = 1e-10;               // absolute tolerance, state units (adaptive methods)
  double dt = 0.0;                   // fixed step [s]: required by fixed-step methods; for ARKODE
                                     // and GSL one-step methods a positive dt turns off adaptivity
  long max_steps = 100000;           // steps allowed per advance() call
  double max_step = 0.0;             // largest step [s], 0 = unlimited (adaptive methods)
  JacobianMode jacobian = JacobianMode::Analytic;
  LinearSolverKind linear_solver = LinearSolverKind::Auto;  // implicit SUNDIALS methods
};

struct IntegratorInfo {
  std::string name;
  std::string family;  // "fixed-step", "CVODE", "ARKODE", "GSL", "exact"
  int order;           // theoretical order; the largest one for variable-order methods,
                       // 0 where there is no single one (extrapolation, the exact solution)
  bool variable_order;
  bool adaptive;            // error-controlled step size
  bool fixed_step_capable;  // can run at a fixed dt (order tests)
  bool implicit;            // uses a Jacobian and a linear solver
  std::string description;
};

class Integrator {
 public:
  struct Outcome {
    double t = 0.0;
    bool root = false;
    std::vector<int> roots_found;  // per root function: +1 rose through 0, -1 fell, 0 none
  };
  virtual ~Integrator() = default;
  // Integrates towards t_out; returns at t_out or at the first root before it. Throws
  // SolverFailure carrying the time reached and the solver's own message.
  virtual Outcome advance(double t_out) = 0;
  // Restarts at (t, y), e.g. after an event changed the state or the right-hand side.
  virtual void reinit(double t, ConstVectorRef y) = 0;
  // Per root function: -1 only falling zeros, +1 only rising, 0 both (the default).
  virtual void set_root_directions(const std::vector<int>& directions) = 0;
  // Time and state of the last return (advance) or restart (reinit): a view by value (a
  // ConstVectorRef, a reference, would dangle).
  virtual double t() const = 0;
  virtual Eigen::Ref<const Vector> y() const = 0;
  // Summed over restarts.
  virtual SolverStats stats() const = 0;
};

const std::vector<IntegratorInfo>& integrator_catalog();
// Whether the method is the exact solution (family "exact"): no step and no tolerance to set.
inline bool is_exact(const IntegratorInfo& info) { return info.family == "exact"; }
// Whether the method needs a fixed step dt (the fixed-step schemes): neither an adaptive method
// nor an exact one takes one.
inline bool needs_step(const IntegratorInfo& info) { return !info.adaptive && !is_exact(info); }
std::vector<std::string> integrator_names();
// Throws std::invalid_argument for an unknown name.
const IntegratorInfo& integrator_info(const std::string& name);

// Whether the integrator reads rtol: an adaptive one stepping by its error estimate, or an
// implicit one at a fixed step (its Newton iteration). An explicit one at a fixed step (a
// fixed-step method, or an adaptive one given dt) has no error control and ignores it.
bool reads_rtol(const IntegratorOptions& options);

// Checks the options against the method; throws std::invalid_argument with a message naming the
// option, the value and what is accepted.
void validate(const IntegratorOptions& options);
std::unique_ptr<Integrator> make_integrator(const IntegratorOptions& options, OdeSystem system, double t0,
                                            ConstVectorRef y0);

// SUNDIALS' version, e.g. "6.4.1", for run metadata.
std::string sundials_version();

std::vector<std::string> linear_solver_names();
std::string_view to_string(LinearSolverKind kind);
LinearSolverKind parse_linear_solver(const std::string& name);  // throws std::invalid_argument
// "analytic" and "dq" (difference quotients), as --jacobian takes them.
std::vector<std::string> jacobian_names();
JacobianMode parse_jacobian(const std::string& name);  // throws std::invalid_argument

}  // namespace contact
