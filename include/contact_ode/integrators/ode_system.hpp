#pragma once
// An ODE y' = f(t, y) as integrators see it: callables only, no model. Optional parts are left
// empty: a sparse Jacobian df/dy with the band that holds it, and root (switching) functions
// g(t, y) whose sign changes the integrator locates. An IMEX split f = f_explicit + f_implicit
// is optional too.
#include "contact_ode/models/linear_algebra.hpp"

#include <cstddef>
#include <functional>
#include <optional>

namespace contact {

struct OdeSystem {
  using Rhs = std::function<void(double t, ConstVectorRef y, VectorRef ydot)>;
  using Jacobian = std::function<void(double t, ConstVectorRef y, SparseMatrix& J)>;
  using Roots = std::function<void(double t, ConstVectorRef y, VectorRef g)>;

  std::size_t size = 0;
  // Which entries are positions q, with q' depending on the velocities only (needed by
  // semi-implicit schemes); empty = no split.
  Mask positions;
  // Which entries are quadratures: integrals of the others (the energy ledger), which no
  // derivative depends on, their own included; empty = none. The exact-linear integrator takes
  // them as quadratic forms of the rest.
  Mask quadratures;
  Rhs rhs;
  Jacobian jacobian;  // empty: none (implicit methods then use difference quotients)
  // The band that holds every non-zero of the Jacobian, where the system knows it (band solvers and
  // preconditioners; the default linear solver takes band storage where it is narrower than the
  // system); none: full.
  std::optional<Bandwidth> bandwidth;
  std::size_t root_count = 0;
  Roots roots;  // empty when root_count == 0
  // IMEX: the stiff part, integrated implicitly, and its Jacobian; the rest of rhs is explicit.
  Rhs implicit_rhs;
  Jacobian implicit_jacobian;
  // IMEX: the explicit part where the system forms it directly (a mechanical system's free flight,
  // one evaluation); empty: rhs - implicit_rhs, two.
  Rhs explicit_rhs;
};

// The system's band, or the full one where it declares none.
inline Bandwidth band_or_full(const OdeSystem& sys) {
  const auto full = static_cast<long>(sys.size) - 1;
  return sys.bandwidth.value_or(Bandwidth{.lower = full, .upper = full});
}

// Whether the system declares a band narrower than itself (Bandwidth::narrower_than).
inline bool has_narrow_band(const OdeSystem& sys) {
  return sys.bandwidth && sys.bandwidth->narrower_than(static_cast<long>(sys.size));
}

}  // namespace contact
