#pragma once
// SUNDIALS CVODE on an OdeSystem: BDF or Adams, Newton iteration with a dense direct linear
// solver, analytic or difference-quotient Jacobian, root finding. Stops at every root so the
// caller can act on it (switch a contact mode, apply an impulse) and re-initialise; statistics
// are summed across re-initialisations.
#include "ode_system.hpp"
#include "solver_stats.hpp"
#include "status.hpp"

#include <memory>
#include <string>
#include <vector>

namespace contact {

enum class CvodeMethod { Bdf, Adams };
enum class JacobianMode { Analytic, DifferenceQuotient };

struct CvodeOptions {
  CvodeMethod method = CvodeMethod::Bdf;
  double rtol = 1e-8;       // relative tolerance
  double atol = 1e-10;      // absolute tolerance (same units as the state)
  long max_steps = 100000;  // steps allowed between two output times
  JacobianMode jacobian = JacobianMode::Analytic;
  double max_step = 0.0;    // largest step [s]; 0 = no limit
};

class CvodeSolver {
 public:
  CvodeSolver(OdeSystem system, double t0, ConstVectorRef y0, const CvodeOptions& options);
  ~CvodeSolver();
  CvodeSolver(CvodeSolver&&) noexcept;
  CvodeSolver& operator=(CvodeSolver&&) noexcept;

  struct Outcome {
    double t = 0.0;
    bool root = false;
    std::vector<int> roots_found;  // per root function: +1 rose through 0, -1 fell, 0 none
  };
  // Integrates towards t_out; returns at t_out or at the first root before it.
  // Throws SolverFailure carrying the time reached and CVODE's message.
  Outcome advance(double t_out);
  // Restarts at (t, y), e.g. after an event changed the state or the right-hand side.
  void reinit(double t, ConstVectorRef y);
  // Per root function: -1 only falling zeros, +1 only rising, 0 both.
  void set_root_directions(const std::vector<int>& directions);

  // Time and state of the last return (advance) or restart (reinit).
  double t() const;
  ConstVectorRef y() const;
  SolverStats stats() const;

  struct Impl;  // opaque; public only so that the C callbacks can name it

 private:
  std::unique_ptr<Impl> impl_;
};

// SUNDIALS' version, e.g. "6.4.1", for run metadata.
std::string sundials_version();

}  // namespace contact
