#include "contact_ode/integrators/integrator.hpp"

#include "contact_ode/models/registry.hpp"

#include "exact_linear_integrator.hpp"
#include "fixed_step_integrator.hpp"
#include "gsl_integrator.hpp"
#include "sundials_integrators.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace contact {

const std::vector<IntegratorInfo>& integrator_catalog() {
  // name, family, order, variable order, adaptive, fixed-step capable, implicit, description
  static const std::vector<IntegratorInfo> catalog = {
      {"euler", "fixed-step", 1, false, false, true, false, "explicit Euler"},
      {"semi-implicit-euler", "fixed-step", 1, false, false, true, false, "semi-implicit (symplectic) Euler"},
      {"velocity-verlet", "fixed-step", 2, false, false, true, false, "velocity Verlet"},
      {"rk4", "fixed-step", 4, false, false, true, false, "classical Runge-Kutta"},
      {"cvode-bdf", "CVODE", 5, true, true, false, true, "CVODE BDF, orders 1-5, Newton"},
      {"cvode-adams", "CVODE", 12, true, true, false, true, "CVODE Adams-Moulton, orders 1-12, Newton"},
      {"arkode-erk", "ARKODE", 4, false, true, true, false, "ARKODE ERKStep, explicit RK"},
      {"arkode-dirk", "ARKODE", 4, false, true, true, true, "ARKODE ARKStep, diagonally implicit RK"},
      {"arkode-imex", "ARKODE", 4, false, true, true, true, "ARKODE ARKStep IMEX: contact forces implicit"},
      {"gsl-rk8pd", "GSL", 8, false, true, true, false, "GSL Runge-Kutta Prince-Dormand (8,9)"},
      {"gsl-rkf45", "GSL", 5, false, true, true, false,
       "GSL Runge-Kutta-Fehlberg (4,5), propagates the 5th-order solution"},
      {"gsl-msbdf", "GSL", 5, true, true, false, true, "GSL multistep BDF, orders 1-5"},
      {"gsl-bsimp", "GSL", 0, true, true, false, true, "GSL implicit Bulirsch-Stoer (Bader-Deuflhard)"},
      {"exact-linear", "exact", 0, false, false, false, false,
       "the exact solution, to rounding, of a right-hand side affine between switches (linear laws)"},
  };
  return catalog;
}

std::vector<std::string> integrator_names() { return names_of(integrator_catalog()); }

const IntegratorInfo& integrator_info(const std::string& name) {
  return find_named(integrator_catalog(), name, "--integrator");
}

std::vector<std::string> linear_solver_names() {
  return {"auto", "dense", "band", "klu", "gmres", "gmres-band"};
}

std::string_view to_string(LinearSolverKind kind) {
  switch (kind) {
    case LinearSolverKind::Auto:
      return "auto";
    case LinearSolverKind::Dense:
      return "dense";
    case LinearSolverKind::Band:
      return "band";
    case LinearSolverKind::Klu:
      return "klu";
    case LinearSolverKind::Gmres:
      return "gmres";
    case LinearSolverKind::GmresBandPreconditioned:
      return "gmres-band";
  }
  return "?";
}

LinearSolverKind parse_linear_solver(const std::string& name) {
  for (auto k : {LinearSolverKind::Auto, LinearSolverKind::Dense, LinearSolverKind::Band,
                 LinearSolverKind::Klu, LinearSolverKind::Gmres, LinearSolverKind::GmresBandPreconditioned})
    if (to_string(k) == name) return k;
  throw std::invalid_argument(fmt::format("--linear-solver: value '{}' is not one of: {}", name,
                                          fmt::join(linear_solver_names(), ", ")));
}

std::vector<std::string> jacobian_names() { return {"analytic", "dq"}; }

JacobianMode parse_jacobian(const std::string& name) {
  if (name == "analytic") return JacobianMode::Analytic;
  if (name == "dq") return JacobianMode::DifferenceQuotient;
  throw std::invalid_argument(
      fmt::format("--jacobian: value '{}' is not one of: {}", name, fmt::join(jacobian_names(), ", ")));
}

bool reads_rtol(const IntegratorOptions& o) {
  const IntegratorInfo& info = integrator_info(o.method);
  return info.implicit || (info.adaptive && !(o.dt > 0));
}

void validate(const IntegratorOptions& o) {
  const IntegratorInfo& info = integrator_info(o.method);
  auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (!positive(o.rtol) || o.rtol >= 1)
    throw std::invalid_argument(
        fmt::format("--rtol: value '{}' is out of range; accepted range (0, 1)", o.rtol));
  if (!positive(o.atol))
    throw std::invalid_argument(
        fmt::format("--atol: value '{}' is out of range; accepted range (0, inf)", o.atol));
  if (!(std::isfinite(o.dt) && o.dt >= 0))
    throw std::invalid_argument(
        fmt::format("--dt: value '{}' is out of range; accepted range (0, inf)", o.dt));
  if (needs_step(info) && !(o.dt > 0))  // 0 is the default: no step was given
    throw std::invalid_argument(
        fmt::format("--dt: value '{}' is out of range: {} is a fixed-step method and needs a step; accepted "
                    "range (0, inf)",
                    o.dt, o.method));
  if (o.dt > 0 && !info.fixed_step_capable)
    throw std::invalid_argument(fmt::format(
        "--dt: {} cannot run at a fixed step; accepted: 0 (adaptive) or a fixed-step method", o.method));
  if (o.max_steps < 1)
    throw std::invalid_argument(
        fmt::format("--max-steps: value '{}' is out of range; accepted range [1, inf)", o.max_steps));
  if (!(std::isfinite(o.max_step) && o.max_step >= 0))
    throw std::invalid_argument(
        fmt::format("--max-step: value '{}' is out of range; accepted range [0, inf)", o.max_step));
  const bool sundials_implicit = info.implicit && (info.family == "CVODE" || info.family == "ARKODE");
  const bool chosen = o.linear_solver != LinearSolverKind::Auto && o.linear_solver != LinearSolverKind::Dense;
  if (chosen && !sundials_implicit)
    throw std::invalid_argument(
        fmt::format("--linear-solver: value '{}' applies only to implicit SUNDIALS methods (cvode-bdf, "
                    "cvode-adams, arkode-dirk, arkode-imex); {} uses none",
                    to_string(o.linear_solver), o.method));
  // SUNDIALS forms difference-quotient Jacobians only in dense and band storage: KLU with one
  // failed at the first step with an opaque 'linear solver init failed'.
  if (o.linear_solver == LinearSolverKind::Klu && o.jacobian != JacobianMode::Analytic)
    throw std::invalid_argument(
        "--linear-solver: value 'klu' needs the analytic Jacobian (SUNDIALS forms no difference-quotient "
        "Jacobian in sparse storage), but the difference-quotient one was chosen (--jacobian dq, or "
        "the penalty-dq method); accepted with it: dense, band, gmres, gmres-band");
}

std::unique_ptr<Integrator> make_integrator(const IntegratorOptions& o, OdeSystem system, double t0,
                                            ConstVectorRef y0) {
  validate(o);
  const IntegratorInfo& info = integrator_info(o.method);
  if (info.family == "CVODE") return make_cvode(o, std::move(system), t0, y0);
  if (info.family == "ARKODE") return make_arkode(o, std::move(system), t0, y0);
  if (info.family == "GSL") return make_gsl(o, std::move(system), t0, y0);
  if (info.family == "exact") return make_exact_linear(o, std::move(system), t0, y0);
  const FixedStepScheme scheme = o.method == "euler"                 ? FixedStepScheme::ExplicitEuler
                                 : o.method == "semi-implicit-euler" ? FixedStepScheme::SemiImplicitEuler
                                 : o.method == "velocity-verlet"     ? FixedStepScheme::VelocityVerlet
                                                                     : FixedStepScheme::Rk4;
  if (scheme != FixedStepScheme::ExplicitEuler && scheme != FixedStepScheme::Rk4 &&
      system.positions.size() == 0)
    throw std::invalid_argument(
        fmt::format("{} needs a system split into positions and velocities", o.method));
  return make_fixed_step(scheme, o, std::move(system), t0, y0);
}

}  // namespace contact
