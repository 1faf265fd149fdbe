// The implicit (backward) Euler spring: the penalty ODE at a fixed step, y+ = y + h f(t + h, y+),
// each contact's law acting where its switching function is positive at y+. What ODE's ERP/CFM
// and MuJoCo's soft constraints amount to: a spring-damper integrated implicitly, stable at any
// step, and dissipative: on an undamped spring each step multiplies the energy by exactly
// 1 / (1 + w^2 h^2) (tests), the mirror of explicit Euler's 1 + w^2 h^2.
// Solved by Newton's method with the scene's Jacobian (central difference quotients, at the
// iterate's modes, where it has none: a one-sided quotient, or one whose perturbed state chose its
// own modes, straddled a switch and spoiled Newton on a stiff wedge) and an LU, to 1e-12 of the
// state's size (where the correction stalls at rounding: each component's correction within 1e-12
// of the state's size or of its own row's terms): sparse on the Jacobian's fixed pattern (analysed
// once) where the scene declares a narrow band (a chain, a column), dense otherwise (a 1000-ball
// column's dense 2001 x 2001 LU, formed whenever a contact engaged, made its 2 s take over 5
// minutes; the sparse one, 1 s). The LU of I - h J is kept across iterations and steps (a chord
// method, as CVODE keeps its Newton matrix): forming it costs a Jacobian, n right-hand sides by
// difference quotients, and an O(n^3) factorization, against one right-hand side per iteration.
// It is formed again when the modes differ from those it was formed with (the Jacobian jumps
// where a law engages), when the step differs, when an iteration fails to halve the correction,
// and after 20 steps; the converged step is the same to the 1e-12 tolerance.
// The modes: those of the step's start, and in the first solve each contact an iterate engages
// stays engaged (modes that flip with every iterate made Newton wander); a converged solve whose
// own modes differ (a contact held in tension, one engaged only at the end) is solved again from
// the start with its modes, unless it solves the step under them too, to Newton's tolerance (a
// touching row's far contacts, squeezed by 1e-22 m and less: solves_under_own_modes); where solves
// cycle (a dashpot's force jumps where it engages: solved engaged the ball ends apart, solved free,
// inside) the step's solution of least energy is taken, of every solve, not only the cycle's (a
// struck chain's first solve lost energy, the two it cycled between after it gained 50 and 100
// times). A stiff wedge (three 2.5 cm balls, k = 1.2e11) at h = 4e-4 s took another route before:
// modes re-read at every iterate, frozen after 20, reached a root that gained 325 times the energy
// and reported success. A step whose solution gains more than kMaxStepGain (a root that is not the
// motion), and 50 iterations in all without convergence, are a typed ConvergenceFailure.
#include "contact_ode/integrators/capabilities.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/integrators/status.hpp"
#include "time_stepping.hpp"

#include <fmt/format.h>
#include <Eigen/Dense>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace contact {

namespace {

constexpr int kMaxNewton = 50, kMaxLuAge = 20;  // iterations; steps an LU is kept
constexpr double kNewtonTolerance = 1e-12;
// The most a step may gain, as a share of the larger of its own and the run's starting energy.
// Implicit Euler loses energy on a convex potential with dashpots; a curved contact's geometry is
// not convex, and a legitimate step gained at most 4 % (the wedge at h = 1e-2 s, its striker
// moving a third of its radius a step). The roots that are not the motion gained 2000 to 5000
// times (the wedge at 1.5, 3 and 5 ms: the striker passed through a ball's centre in one step).
constexpr double kMaxStepGain = 0.1;

RunResult run(const Dynamics& scene, const Method& m, const SolveOptions& span) {
  const ContactGeometry& geo = contact_geometry(scene);
  const std::size_t nc = scene.contact_count();
  const auto n = static_cast<Eigen::Index>(scene.state_size());
  ContactModes modes, formed_with, live;  // Newton's modes; those the LU was formed with; the iterate's
  std::vector<ContactModes> settled;      // the modes of this step's converged solves
  std::vector<Vector> solutions;          // and their solutions
  SparseMatrix J;
  const bool sparse = scene.has_jacobian() && scene.jacobian_bandwidth().narrower_than(n);
  Eigen::MatrixXd A(sparse ? 0 : n, sparse ? 0 : n);
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(sparse ? 0 : n);  // sized once: iterations allocate nothing
  SparseMatrix S;                                           // I - h J on the Jacobian's pattern
  Eigen::SparseLU<SparseMatrix> sparse_lu;
  bool analysed = false;
  int lu_age = -1;      // steps since the LU was formed; < 0: none
  double formed_h = 0;  // the step it was formed for (a run's last may be shorter)
  Vector z(n), f(n), fp(n), fm(n), G(n), zp(n), dz(n), terms(n);
  // I - h J at (t, z) with the iterate's modes, factorized.
  auto form = [&](double t, double h, SolverStats& stats) {
    if (scene.has_jacobian()) {
      scene.jacobian(t, z, modes, J);
      if (sparse)
        S = -h * J;
      else
        A = -h * J;
    } else {  // difference quotients, column by column
      for (Eigen::Index j = 0; j < n; ++j) {
        const double dj = 1e-7 * std::max(1.0, std::abs(z[j]));
        zp = z;
        zp[j] += dj;
        scene.rhs(t, zp, modes, fp);  // the iterate's modes: a column must not straddle a switch
        zp[j] = z[j] - dj;
        scene.rhs(t, zp, modes, fm);
        A.col(j) = -h * (fp - fm) / (2 * dj);
      }
      stats.rhs_evals += 2 * n;
    }
    if (sparse) {
      for (Eigen::Index j = 0; j < n; ++j) S.coeffRef(j, j) += 1.0;  // on the pattern (Dynamics::jacobian)
      if (!analysed) sparse_lu.analyzePattern(S);  // the pattern is the same whatever the modes
      analysed = true;
      sparse_lu.factorize(S);
      if (sparse_lu.info() != Eigen::Success)
        throw SolverFailure(
            Status::ConvergenceFailure, t,
            fmt::format("implicit Euler: I - h J is singular ({})", sparse_lu.lastErrorMessage()));
    } else {
      A.diagonal().array() += 1.0;
      lu.compute(A);
    }
    formed_with = modes;
    formed_h = h;
    lu_age = 0;
    stats.jac_evals += 1;
    stats.linear_setups += 1;
  };
  // Whether z, converged under `modes`, also solves the step under its own modes `live`: whether
  // its residual under them, which differs only by h times the forces of the contacts whose modes
  // differ, is within Newton's tolerance. A correction is then no larger (I - h J's inverse does
  // not amplify a residual: a spring's shortens it by 1 + w^2 h^2), and another solve would move
  // the state by less than the tolerance to which it was solved. A struck row of 50 touching balls
  // at h = 1e-6 s squeezed each contact 1e-5 times as hard as the one before, down to 1e-22 m
  // (a force of 1e-16 N): each solve engaged one more contact, which engaged the next, and the
  // step failed, "the contacts' modes did not settle in 50 iterations (24 solves)".
  auto solves_under_own_modes = [&](double t1, double h, double state, SolverStats& stats) {
    scene.rhs(t1, z, modes, fp);
    scene.rhs(t1, z, live, fm);
    stats.rhs_evals += 2;
    return h * (fm - fp).lpNorm<Eigen::Infinity>() <= kNewtonTolerance * state;
  };
  SpringSwitches switches(nc);
  double e_start = std::numeric_limits<double>::quiet_NaN();
  auto step = [&](double t, double h, Vector& y, StepReport& report, SolverStats& stats) {
    switches.before(geo, y);
    z = y;
    geo.modes_from_state(nc, z, modes);
    settled.clear();
    solutions.clear();
    if (lu_age >= 0) ++lu_age;
    double previous = std::numeric_limits<double>::infinity();  // the last correction's size
    // The first solve's iterations that engaged a contact do not count against kMaxNewton: each one
    // is progress, and there are at most as many as contacts. A row of 50 touching balls struck at
    // h = 1e-3 s (w h = 6.3) engages one contact further down the row an iterate, and failed at the
    // first touch, 'Newton did not converge in 50 iterations (last correction 9.3e-08)'.
    int engaging = 0;
    for (int it = 1;; ++it) {
      if (settled.empty()) {
        geo.modes_from_state(nc, z, live);
        bool engaged = false;
        for (std::size_t i = 0; i < nc; ++i)
          if (live[i] == ContactMode::Penalty && modes[i] != ContactMode::Penalty) {
            modes[i] = ContactMode::Penalty;
            engaged = true;
          }
        engaging += engaged ? 1 : 0;
      }
      scene.rhs(t + h, z, modes, f);
      stats.rhs_evals += 1;
      G = z - y - h * f;
      if (lu_age < 0 || lu_age > kMaxLuAge || modes != formed_with || h != formed_h) form(t + h, h, stats);
      stats.newton_iters += 1;
      if (sparse)
        dz = sparse_lu.solve(G);
      else
        dz = lu.solve(G);
      z -= dz;
      // Relative to the state's size, as the header says: (1 + |z|) made it 1e-12 in the state's
      // units, and a drop scaled to picometres (h0 = 1e-12 m, g scaled alike) stopped at a first
      // iterate of its size: its contacts moved by 26 ms and its exit speed by 12 %.
      const double size = dz.lpNorm<Eigen::Infinity>();
      const double state = std::max(z.lpNorm<Eigen::Infinity>(), y.lpNorm<Eigen::Infinity>());
      // Below the smallest normal double a number keeps no relative digits (subnormals are
      // 4.9e-324 apart), so a correction that small is converged at any state: an undamped
      // spring-mass decaying under implicit Euler (w h = 2) reached 1e-309 m at t = 18 s, where
      // its corrections stalled at 2e-322, against a bound of 1e-321, and the run failed.
      bool converged = size <= std::max(kNewtonTolerance * state, std::numeric_limits<double>::min());
      // A correction that no longer halves may be the residual's rounding, which the state's size
      // does not bound: at rest on a spring, gravity and the spring cancel in f, and the velocity
      // part of G rounds at the size of h g and h k x / m, not of the state. A drop sped up 1000
      // times (g and k times 1e6, the step 1e-3 as long: the same motion) stalled at corrections of
      // 4.6e-16 against a bound of 1e-16 and the run failed. Each component is then measured
      // against the larger of the state's size and its own residual's terms, |y| + |I - h J| |z|,
      // at the same 1e-12: a component far smaller than the state need not be resolved below the
      // state's tolerance. Measured against its own terms alone, such a component kept an
      // off-centre hit at k = 1e10 N/m, w h = 8.6, from stopping: a spin component of 5e-19 moved
      // by 8e-29, the LU's mixing of the other rows' rounding, against a bound of 9e-31, while the
      // largest correction was at its own row's rounding (50 iterations, and the run failed).
      if (size > 0.5 * previous) {
        if (sparse)
          terms = S.cwiseAbs() * z.cwiseAbs();
        else
          terms.noalias() = A.cwiseAbs() * z.cwiseAbs();
        terms += y.cwiseAbs();
        converged = converged || (dz.array().abs() <= kNewtonTolerance * terms.array().max(state)).all();
      }
      if (converged) {
        geo.modes_from_state(nc, z, live);
        if (live == modes || solves_under_own_modes(t + h, h, state, stats)) {
          modes = live;
          break;
        }
        if (std::find(settled.begin(), settled.end(), live) != settled.end()) {
          // No solve's modes are its own: a damped contact's force jumps where it engages, and
          // the ball ends apart when pushed, inside when not. Of the step's solutions, the one of
          // least energy: another stores a spring's energy that no force put there (a ball
          // drop's 9.8 J became 9e10 J in one step).
          for (std::size_t s = 0; s < settled.size(); ++s) {
            if (scene.energy(solutions[s]) < scene.energy(z)) {
              z = solutions[s];
              modes = settled[s];
            }
          }
          break;
        }
      }
      // An iterate that left the doubles (the wedge at k = 1e300 N/m) read "did not converge (last
      // correction nan); a shorter step starts Newton nearer the motion", a remedy no practical
      // step gives there: it is a non-finite state, said so.
      if (!z.allFinite())
        throw SolverFailure(
            Status::NonFiniteState, t,
            fmt::format("implicit Euler: Newton's iterate is not finite after {} iteration(s) "
                        "at dt = {:g} s: the contact forces or the step's matrix I - h J left "
                        "the doubles' range at these settings",
                        it, h));
      // Newton starts at the step's start, and a step that carries a body past a contact starts it
      // far from its root: the wedge's 0.7 to 0.9 mm balls, struck at 2 m/s, failed so at 1 ms
      // steps and ran at 0.3 ms. The message names that remedy, as the energy check's does.
      if (it == kMaxNewton + engaging) {
        const std::string why =
            converged
                ? fmt::format("the contacts' modes did not settle in {} iterations ({} solves)", it,
                              settled.size() + 1)
                : fmt::format("Newton did not converge in {} iterations (last correction {:g})", it, size);
        throw SolverFailure(
            Status::ConvergenceFailure, t,
            fmt::format("implicit Euler: {} at dt = {:g} s; a shorter step starts Newton nearer the motion",
                        why, h));
      }
      if (converged) {  // a contact held in tension, or one newly engaged: solve again
        settled.push_back(modes);
        solutions.push_back(z);
        modes = live;
        z = y;
        previous = std::numeric_limits<double>::infinity();
        continue;
      }
      if (size > 0.5 * previous) lu_age = -1;  // too slow for the kept matrix: form it at the iterate
      previous = size;
    }
    scene.normalize(z);
    const double e_before = scene.energy(y), e_after = scene.energy(z);
    if (std::isnan(e_start)) e_start = e_before;
    if (e_after - e_before > kMaxStepGain * std::max(std::abs(e_before), std::abs(e_start)))
      throw SolverFailure(
          Status::ConvergenceFailure, t,
          fmt::format("implicit Euler: Newton reached a root that is not the motion: the "
                      "step gained {:.3g} J ({:.3g} to {:.3g} J), where implicit Euler "
                      "loses energy; a shorter step than dt = {:g} s keeps it near the motion",
                      e_after - e_before, e_before, e_after, h));
    y = z;
    report.dissipated += switches.released(geo, y);
    // The laws that acted are those of the modes y was solved with: a contact engaged and let go
    // within the step pushed. Its dashpot's work is booked only where its law is on at y: a
    // solve engaged that ends apart holds its contact in tension, and h c v^2 at the separating
    // speed is not what it lost (a rubber ball at k = 1e10 N/m, h = 1e-4 s booked 5 times its
    // energy).
    geo.modes_from_state(nc, y, live);
    for (std::size_t i = 0; i < nc; ++i) {
      if (modes[i] == ContactMode::Penalty) report.push[i] = 1.0;
      if (live[i] == ContactMode::Penalty) report.dissipated += h * geo.dissipated_power(i, y);
    }
  };
  return run_time_stepping(scene, m.name, m.dt, step, span, true, &m);
}

}  // namespace

std::vector<MethodInfo> implicit_spring_methods() {
  return {{.name = "game-implicit-spring",
           .description = "implicit (backward) Euler at fixed dt, penalty spring force (ODE's ERP/CFM, "
                          "MuJoCo's soft contacts)",
           .family = "game",
           .fixed_step = true,
           .uses_contact_law = true,
           .needs = "dynamics and contact geometry",
           .can_run = [](const Dynamics&) { return true; },
           .run = run,
           .settings = {"dt"},
           // its sparse LU: 78 doubles per entry on a chain, 122 on a stack (measured)
           .working_doubles = 160}};
}

}  // namespace contact
