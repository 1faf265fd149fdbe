// Moreau–Jean time stepping (Moreau 1988, Jean 1999; Siconos' MoreauJeanOSI with an LCP): the
// event-capturing scheme of nonsmooth mechanics. Each step of h:
//   v+ = v + h a(q, v) + M^-1 J^T P,     q+ = q + h ((1 - theta) v + theta v+),
// with the impulses P of the contacts predicted to be closed (g + h/2 g' <= 0, Siconos' index
// set) the solution of Newton's impact law at the velocity level, a linear complementarity
// problem:  0 <= u+_i + e_i u_i  _|_  P_i >= 0,  u the gap rates before the step. The LCP is
// solved by projected Gauss–Seidel, warm-started from the last step's impulses, to 1e-12 of the
// largest gap rate before or after the forces' update, or to the gap rates' rounding error if that
// is larger. Gauss–Seidel needs ~3 n^2 sweeps for that on a row of n touching contacts, so after
// 100 sweeps the step's LCP is solved exactly instead (lcp.hpp: block principal pivoting from
// Gauss–Seidel's guess, up to 3000 closed contacts), and the sweeps go on from its answer (a
// failure to converge in 10000 is a typed ConvergenceFailure). With one contact u+ = -e u
// exactly, at every step: the restitution is that of the law, whatever h (tests).
#include "contact_ode/integrators/capabilities.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/integrators/status.hpp"
#include "lcp.hpp"
#include "time_stepping.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace contact {

namespace {

constexpr int kMaxSweeps = 10000;
constexpr int kSweepsBeforeExact = 100;
// The most closed contacts solved exactly: forming W asks n^2 gap rates (below), 9e6 at 3000 (a
// few tens of ms), 1e10 for a 1e5-ball column. Beyond it Gauss–Seidel goes on alone.
constexpr std::size_t kMaxExact = 3000;
constexpr double kLcpTolerance = 1e-12;

// The active contacts' LCP solved exactly (lcp.hpp); on success P and y carry its impulses. W's
// column j is the gap rates' change under contact j's impulse of a unit change of its own rate
// (scaled so that a heavy body's column is not lost in the rounding of y's velocities); b is what
// the rates would be with no impulse at all: the current rates (Newton's target folded in) less
// the impulses already applied. Counted in stats as a Jacobian (W) and its block factorisations.
bool solve_exactly(const ContactGeometry& geo, const NormalImpulses& normal, const ImpulseMap& law,
                   const std::vector<bool>& active, const std::vector<double>& u0, double w_tol,
                   std::vector<double>& P, Vector& y, SolverStats& stats) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < active.size(); ++i)
    if (active[i]) idx.push_back(i);
  const auto n = static_cast<Eigen::Index>(idx.size());
  Eigen::VectorXd now(n), rate(n), applied(n);
  Vector pushed;
  for (Eigen::Index r = 0; r < n; ++r) {
    const std::size_t i = idx[static_cast<std::size_t>(r)];
    now(r) = geo.gap_rate(i, y);
    rate(r) = now(r) + law.restitution(i) * u0[i];
    applied(r) = P[i];
  }
  // Sparse: an impulse changes only its own bodies' velocities, so the rates of the contacts that
  // share none of them come out exactly unchanged (the same arithmetic on the same numbers), and
  // their entries are left out. Forming W still asks every rate for every column (n^2 rates, the
  // geometry says nothing of which bodies a contact joins): 9e6 at 3000 contacts, a few tens of ms.
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index c = 0; c < n; ++c) {
    const std::size_t j = idx[static_cast<std::size_t>(c)];
    const double lambda = 1 / normal.inverse_mass(j, y);
    pushed = y;
    normal.apply_normal_impulse(j, lambda, pushed);
    for (Eigen::Index r = 0; r < n; ++r)
      if (const double change = geo.gap_rate(idx[static_cast<std::size_t>(r)], pushed) - now(r); change != 0)
        entries.emplace_back(r, c, change / lambda);
  }
  Eigen::SparseMatrix<double> W(n, n);
  W.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SparseMatrix<double> transposed = W.transpose();
  W = 0.5 * (W + transposed);
  // The guess: the contacts Gauss–Seidel pushes, and those it leaves closing or still (w <= 0),
  // which are as likely to carry load. Gauss–Seidel's pushes alone missed the top of a falling
  // column: its balls fall together, at gap rates of exactly zero, so a block solve found only
  // the lowest of them short (w < 0) and pivoting added one contact per solve (a 1000-ball column
  // at dt = 0.1 ms: 850 dense solves, 7 s for one step; now one).
  std::vector<bool> positive(idx.size());
  for (std::size_t r = 0; r < idx.size(); ++r)
    positive[r] = P[idx[r]] > 0 || rate(static_cast<Eigen::Index>(r)) <= w_tol;
  // Block pivoting from a good guess takes a few solves (21 for 200 contacts from a wrong one, Lcp
  // tests); the bound leaves Murty's single flips room for a few passes over the contacts.
  const LcpSolution s = solve_lcp(W, rate - W * applied, positive, w_tol, 4 * static_cast<int>(n) + 16);
  stats.jac_evals += 1;
  stats.linear_setups += s.solves;
  if (!s.solved) return false;
  for (Eigen::Index r = 0; r < n; ++r) {
    const std::size_t i = idx[static_cast<std::size_t>(r)];
    normal.apply_normal_impulse(i, s.p(r) - P[i], y);
    P[i] = s.p(r);
  }
  return true;
}

RunResult run(const Dynamics& scene, const Method& m, const SolveOptions& span) {
  const ContactGeometry& geo = contact_geometry(scene);
  const NormalImpulses& normal = normal_impulses(scene, m.name);
  const ImpulseMap& law = impulse_map(scene, m.name);
  const std::size_t nc = scene.contact_count();
  std::vector<double> P(nc), u0(nc), restitution(nc);
  std::vector<bool> active(nc), fresh(nc);
  for (std::size_t i = 0; i < nc; ++i) restitution[i] = law.restitution(i);
  FreeMotion motion(scene);
  Vector v_old, blended;
  auto step = [&](double t, double h, Vector& y, StepReport& report, SolverStats& stats) {
    for (std::size_t i = 0; i < nc; ++i) {
      u0[i] = geo.gap_rate(i, y);
      const bool was = active[i];
      active[i] = geo.gap(i, y) + 0.5 * h * u0[i] <= kContactMargin;
      if (!active[i] || !was) P[i] = 0;
      fresh[i] = active[i] && !was;
    }
    v_old = y;
    stats.rhs_evals += motion.add_velocity(t, h, y);
    double scale = 0;
    for (std::size_t i = 0; i < nc; ++i) {
      if (!active[i]) continue;
      scale = std::max({scale, std::abs(u0[i]), std::abs(geo.gap_rate(i, y))});
      normal.apply_normal_impulse(i, P[i], y);  // warm start
    }
    // The gap rates come from the state's entries, so they carry a rounding error of about eps
    // times the largest: a floor no sweep goes below. (A box spinning at 4 rad/s touching at
    // 8e-5 m/s was asked for 1e-12 of that, 8e-17 m/s, and failed at 1e-16 after 10000 sweeps.)
    const double round_off = 64 * std::numeric_limits<double>::epsilon() * y.cwiseAbs().maxCoeff();
    const auto closed = static_cast<std::size_t>(std::count(active.begin(), active.end(), true));
    for (int sweep = 1;; ++sweep) {
      double change = 0;
      for (std::size_t i = 0; i < nc; ++i) {
        if (!active[i]) continue;
        const double w = normal.inverse_mass(i, y);
        const double dP =
            accumulate_impulse(normal, i, -(geo.gap_rate(i, y) + law.restitution(i) * u0[i]) / w, P[i], y);
        change = std::max(change, std::abs(dP) * w);
      }
      stats.newton_iters += 1;
      const double tolerance = std::max(kLcpTolerance * scale, round_off);
      if (change <= tolerance || change == 0) break;
      if (sweep == kSweepsBeforeExact && closed <= kMaxExact)
        solve_exactly(geo, normal, law, active, u0, tolerance, P, y, stats);
      if (sweep == kMaxSweeps)
        throw SolverFailure(
            Status::ConvergenceFailure, t,
            fmt::format("Moreau-Jean: the impact LCP did not converge in {} Gauss-Seidel sweeps "
                        "(last change {:g} m/s){}",
                        kMaxSweeps, change,
                        closed > kMaxExact
                            ? fmt::format("; its {} closed contacts are more than the {} solved "
                                          "exactly (n^2 gap rates to form the Delassus matrix)",
                                          closed, kMaxExact)
                            : ""));
    }
    for (std::size_t i = 0; i < nc; ++i) report.push[i] = active[i] ? P[i] * normal.inverse_mass(i, y) : 0.0;
    report.dissipated += impact_losses(geo, normal, y, active, fresh, u0, restitution, P);
    // q+ = q + h ((1 - theta) v + theta v+): the positions advanced with the blended velocities.
    blended = (1 - m.theta) * v_old + m.theta * y;
    stats.rhs_evals += motion.advance_positions(t, h, blended);
    motion.copy_positions(blended, y);
  };
  return run_time_stepping(scene, m.name, m.dt, step, span, false);
}

}  // namespace

std::vector<MethodInfo> moreau_jean_methods() {
  return {impulse_stepping_method("moreau-jean",
                                  "Moreau-Jean time stepping: theta = 1/2, Newton's impact law as one LCP "
                                  "per step (Siconos)",
                                  run, {"dt", "theta"})};
}

}  // namespace contact
