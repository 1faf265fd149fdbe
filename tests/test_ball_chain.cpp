// The N-ball chain: its analytic Jacobian, band and sparse storage, every linear solver on the
// same penalty run, and Newton's cradle by sequential impulses.
#include "contact_ode/integrators/event_driven.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_chain.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "sundials_linear_solver.hpp"

#include <gtest/gtest.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <cmath>
#include <optional>

using namespace contact;

namespace {

BallChain chain(std::size_t n, ContactLaw law, double e = 1.0) {
  BallChainParams p;
  p.n = n;
  p.law = law;
  p.e = e;
  return BallChain(p);
}

// A mid-collision state: every contact overlapping a little, with spread velocities.
Vector compressed_state(const BallChain& c) {
  Vector y = c.initial_state();
  for (Eigen::Index k = 0; k < y.size(); k += 2) {
    y[k] -= 1e-5 * static_cast<double>(k);  // each gap closes by 2e-5 m
    y[k + 1] = 0.3 - 0.1 * static_cast<double>(k);
  }
  return y;
}

Matrix dense_of(SUNMatrix A, Eigen::Index n) {
  Matrix M = Matrix::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      if (SUNMatGetID(A) == SUNMATRIX_DENSE) M(i, j) = SM_ELEMENT_D(A, i, j);
      if (SUNMatGetID(A) == SUNMATRIX_BAND && i - j <= SUNBandMatrix_LowerBandwidth(A) &&
          j - i <= SUNBandMatrix_UpperBandwidth(A))
        M(i, j) = SM_ELEMENT_B(A, i, j);
    }
  if (SUNMatGetID(A) == SUNMATRIX_SPARSE) {
    const sunindextype* col = SUNSparseMatrix_IndexPointers(A);
    for (Eigen::Index j = 0; j < n; ++j)
      for (sunindextype k = col[j]; k < col[j + 1]; ++k)
        M(SUNSparseMatrix_IndexValues(A)[k], j) = SUNSparseMatrix_Data(A)[k];
  }
  return M;
}

}  // namespace

// Central differences: truncation vanishes (the forces are affine in the state within a mode)
// and rounding is eps |f| / h ~ 1e-10 relative with h = 1e-7 m.
TEST(BallChain, JacobianMatchesCentralDifferencesInEveryMode) {
  for (const ContactLaw& law :
       {ContactLaw{Hooke{1e6}}, ContactLaw{kelvin_voigt_for_restitution(1e6, 0.1, 0.7, false)}}) {
    const BallChain c = chain(6, law);
    const Vector y = compressed_state(c);
    for (auto mode : {ContactMode::Free, ContactMode::Penalty}) {
      const ContactModes modes(c.contact_count(), mode);
      SparseMatrix J;
      c.jacobian(0.0, y, modes, J);
      const auto n = y.size();
      Matrix numeric(n, n);
      Vector yp = y, ym = y, fp(n), fm(n);
      for (Eigen::Index j = 0; j < n; ++j) {
        yp[j] += 1e-7;
        ym[j] -= 1e-7;
        c.rhs(0, yp, modes, fp);
        c.rhs(0, ym, modes, fm);
        numeric.col(j) = (fp - fm) / 2e-7;
        yp[j] = ym[j] = y[j];
      }
      const Matrix analytic(J);
      EXPECT_LE((analytic - numeric).cwiseAbs().maxCoeff(),
                1e-7 * std::max(1.0, numeric.cwiseAbs().maxCoeff()));
      // Every non-zero lies in the declared band, and the band is no wider than needed.
      long lower = 0, upper = 0;
      for (int j = 0; j < J.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(J, j); it; ++it) {
          lower = std::max(lower, static_cast<long>(it.row()) - j);
          upper = std::max(upper, j - static_cast<long>(it.row()));
        }
      EXPECT_EQ(lower, c.jacobian_bandwidth().lower);
      for (Eigen::Index d = 0; d < J.rows(); ++d)
        EXPECT_TRUE(J.coeff(d, d) == J.coeff(d, d) &&
                    [&] {
                      for (SparseMatrix::InnerIterator it(J, d); it; ++it)
                        if (it.row() == d) return true;
                      return false;
                    }())
            << "diagonal entry " << d << " missing from the pattern";
      EXPECT_EQ(upper, c.jacobian_bandwidth().upper);
      // The pattern does not depend on the mode (sparse factorisations reuse it).
      SparseMatrix J_free;
      c.jacobian(0.0, y, ContactModes(c.contact_count(), ContactMode::Free), J_free);
      EXPECT_EQ(J.nonZeros(), J_free.nonZeros());
    }
  }
}

TEST(BallChain, BandAndSparseStorageHoldTheDenseJacobian) {
  const BallChain c = chain(7, Hooke{1e6});
  const Vector y = compressed_state(c);
  SparseMatrix J;
  c.jacobian(0.0, y, ContactModes(c.contact_count(), ContactMode::Penalty), J);
  const auto n = static_cast<sunindextype>(y.size());
  const Matrix dense(J);
  contact::sundials::Context ctx = contact::sundials::make_context();
  contact::sundials::Matrix A_dense(SUNDenseMatrix(n, n, ctx.get()));
  const Bandwidth band = c.jacobian_bandwidth();
  contact::sundials::Matrix A_band(SUNBandMatrix(n, band.upper, band.lower, ctx.get()));
  contact::sundials::Matrix A_sparse(SUNSparseMatrix(n, n, 1, CSC_MAT, ctx.get()));  // grows on copy
  for (SUNMatrix A : {A_dense.get(), A_band.get(), A_sparse.get()}) {
    ASSERT_TRUE(contact::sundials::copy_jacobian(J, A));
    EXPECT_EQ(dense_of(A, y.size()), dense) << "matrix id " << SUNMatGetID(A);
  }
  // A band too narrow for the Jacobian is refused, not silently truncated.
  contact::sundials::Matrix narrow(SUNBandMatrix(n, band.upper, band.lower - 1, ctx.get()));
  EXPECT_FALSE(contact::sundials::copy_jacobian(J, narrow.get()));
}

// Every linear solver must produce the same trajectory: they solve the same Newton systems, to
// the same tolerance (rtol 1e-9). Final velocities agree to 1e-6 of the striker speed.
TEST(BallChain, EveryLinearSolverGivesTheSamePenaltyRun) {
  const BallChain c = chain(8, Hooke{1e6});
  PenaltyOptions o;
  SolveOptions o_span;
  o_span.t_end = 0.05;
  o_span.sample_dt = 0.05;
  o.integrator.rtol = 1e-9;
  o.integrator.atol = 1e-12;
  const RunResult ref = run_penalty(c, o, o_span);
  ASSERT_TRUE(ref.ok()) << ref.message;
  for (const char* method : {"cvode-bdf", "arkode-dirk"})
    for (auto ls :
         {LinearSolverKind::Auto, LinearSolverKind::Dense, LinearSolverKind::Band, LinearSolverKind::Klu,
          LinearSolverKind::Gmres, LinearSolverKind::GmresBandPreconditioned}) {
      o.integrator.method = method;
      o.integrator.linear_solver = ls;
      const RunResult r = run_penalty(c, o, o_span);
      ASSERT_TRUE(r.ok()) << method << " " << to_string(ls) << ": " << r.message;
      const Vector& y = r.samples.back().y;
      const Vector& y_ref = ref.samples.back().y;
      for (Eigen::Index k = 1; k < y.size(); k += 2)
        EXPECT_NEAR(y[k], y_ref[k], 1e-6 * c.params().v0) << method << " " << to_string(ls) << " v" << k / 2;
    }
}

// The default linear solver, auto, is the band one where the Jacobian's band is narrower than the
// system, and dense where it is not. Dense was the default: a 200-ball Hooke column's penalty run
// took 293 s where band takes 20 s (bench_chain: band 3.5 to 4x faster than dense at 100 balls, 70 to 80x at
// 1000). The two are told apart by difference quotients: CVODE's band quotients cost bandwidth + 1 right-hand
// sides per Jacobian, the dense ones one per state (with the analytic Jacobian the two factorisations gave
// the same run to the bit here).
TEST(BallChain, TheDefaultLinearSolverIsBandOnAChainAndDenseOnABall) {
  const auto run = [](const Dynamics& scene, std::optional<LinearSolverKind> ls) {
    PenaltyOptions o;
    o.integrator.jacobian = JacobianMode::DifferenceQuotient;
    if (ls) o.integrator.linear_solver = *ls;
    const RunResult r = run_penalty(scene, o, {.t_end = 0.05, .sample_dt = 0.05});
    EXPECT_TRUE(r.ok()) << r.message;
    return r;
  };
  const BallChain c = chain(20, Hooke{1e6});
  const RunResult by_default = run(c, std::nullopt), band = run(c, LinearSolverKind::Band),
                  dense = run(c, LinearSolverKind::Dense);
  EXPECT_EQ(by_default.stats.rhs_evals, band.stats.rhs_evals);
  EXPECT_EQ(by_default.samples.back().y, band.samples.back().y);
  EXPECT_GT(dense.stats.rhs_evals, band.stats.rhs_evals);
  // One ball and its ledger: a full band, so dense.
  const BallDrop ball({.law = KelvinVoigt{1e5, 44.8}});
  const RunResult ball_default = run(ball, std::nullopt), ball_dense = run(ball, LinearSolverKind::Dense);
  EXPECT_EQ(ball_default.stats.rhs_evals, ball_dense.stats.rhs_evals);
  EXPECT_EQ(ball_default.samples.back().y, ball_dense.samples.back().y);
}

// Sequential impulses with e = 1 on touching equal balls: each contact swaps the two velocities,
// so the striker stops and the last ball leaves at v0, exactly (to rounding).
TEST(BallChain, NewtonsCradleBySequentialImpulsesPassesTheVelocityToTheLastBall) {
  for (std::size_t n : {2, 3, 5, 10}) {
    const BallChain c = chain(n, Hooke{1e6}, 1.0);
    EventOptions o;
    SolveOptions o_span;
    o_span.t_end = 0.1;
    o_span.sample_dt = 0.1;
    const RunResult r = run_event_driven(c, o, o_span);
    ASSERT_TRUE(r.ok()) << r.message;
    const Vector& y = r.samples.back().y;
    for (std::size_t b = 0; b + 1 < n; ++b)
      EXPECT_NEAR(y[static_cast<Eigen::Index>(2 * b + 1)], 0.0, 1e-14) << "ball " << b;
    EXPECT_NEAR(y[static_cast<Eigen::Index>(2 * n - 1)], c.params().v0, 1e-14);
    EXPECT_EQ(r.contacts.size(), n - 1);
  }
}

TEST(BallChain, RefusesFewerThanTwoBalls) {
  BallChainParams p;
  p.n = 1;
  EXPECT_THROW(BallChain{p}, std::invalid_argument);
}

// A method without the contact springs (impulses, constraints, an engine's own contacts) measured
// the scene's energy less its springs' (RunRecorder::exclude_spring_energy), a subtraction that at a
// stiff law loses the motion: touching balls overlap by rounding (1e-17 m), whose springs at
// k = 1e300 hold 1e268 J, and the cradle's 0.05 J went to 0 (an 'energy error' of 100 %). The law's
// k must not enter such a method's energy at all: each one's samples, at k = 1e6 and 1e300, agree
// to rounding.
TEST(BallChain, AMethodWithoutSpringsMeasuresTheSameEnergyWhateverTheLawsStiffness) {
  const auto cradle = [](double k) {
    return make_scene("ball-chain", {{"n", 5.0}, {"e", 1.0}, {"k", k}}, "hooke");
  };
  const auto soft = cradle(1e6), stiff = cradle(1e300);
  int compared = 0;
  for (const auto& name : methods_for(*soft)) {
    const MethodInfo& info = method_info(name);
    if (info.uses_contact_law) continue;
    const Method m{.name = name, .dt = info.fixed_step ? 1e-5 : 0.0};
    const SolveOptions span{.t_end = 0.05, .sample_dt = 0.01};
    const RunResult a = solve(*soft, m, span), b = solve(*stiff, m, span);
    if (!a.ok()) continue;  // (ODE's pivoting LCP stops on touching balls, whatever k)
    ASSERT_TRUE(b.ok()) << name << ": " << b.message;
    ASSERT_EQ(a.samples.size(), b.samples.size()) << name;
    for (std::size_t s = 0; s < a.samples.size(); ++s)
      EXPECT_NEAR(b.samples[s].energy, a.samples[s].energy, 1e-12 * a.energy0) << name << " sample " << s;
    ++compared;
  }
  EXPECT_GE(compared, 6);  // the game loops, event-driven, sequential impulses, Moreau-Jean, ...
}
