#pragma once
// An ODE y' = f(t, y) as integrators see it: callables only, no model. Optional parts are left
// empty: a sparse Jacobian df/dy with the band that holds it, and root (switching) functions
// g(t, y) whose sign changes the integrator locates. An IMEX split f = f_explicit + f_implicit
// is optional too.
#include "contact_ode/models/linear_algebra.hpp"

#include <cstddef>
#include <functional>

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
  Jacobian jacobian;    // empty: none (implicit methods then use difference quotients)
  Bandwidth bandwidth;  // of the Jacobian; used by band solvers and preconditioners
  std::size_t root_count = 0;
  Roots roots;  // empty when root_count == 0
  // IMEX: the stiff part, integrated implicitly, and its Jacobian; the rest of rhs is explicit.
  Rhs implicit_rhs;
  Jacobian implicit_jacobian;
  // IMEX: the explicit part where the system forms it directly (a mechanical system's free flight,
  // one evaluation); empty: rhs - implicit_rhs, two.
  Rhs explicit_rhs;
};

}  // namespace contact
