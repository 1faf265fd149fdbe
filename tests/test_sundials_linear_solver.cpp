// The linear systems make_linear_system builds (integrators/sundials_linear_solver.hpp). KLU keeps
// its symbolic analysis when CVODE or ARKODE initialise it again after a re-initialisation (a
// restart at every contact switch), and redoes it for a matrix of another pattern.
#include "sundials_handles.hpp"
#include "sundials_linear_solver.hpp"

#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace klu_analysis_test {

using namespace contact::sundials;

constexpr sunindextype kKluSize = 6;

// A in CSC: column j holds the diagonal (4 + j + shift) and -1 in each row of rows_of(j).
template <class RowsOf>
void fill(SUNMatrix A, RowsOf rows_of, double shift) {
  sunindextype* ptr = SM_INDEXPTRS_S(A);
  sunindextype* row = SM_INDEXVALS_S(A);
  sunrealtype* val = SM_DATA_S(A);
  sunindextype k = 0;
  for (sunindextype j = 0; j < kKluSize; ++j) {
    ptr[j] = k;
    for (sunindextype i = 0; i < kKluSize; ++i) {
      const std::vector<sunindextype> off = rows_of(j);
      const bool offdiag = std::find(off.begin(), off.end(), i) != off.end();
      if (i != j && !offdiag) continue;
      row[k] = i;
      val[k++] = i == j ? 4.0 + static_cast<double>(j) + shift : -1.0;
    }
  }
  ptr[kKluSize] = k;
}

// The residual of x in A x = b (A in CSC): its largest entry, max |A x - b|, and the scale that
// rounding's backward error is measured against, max_i sum_j |A_ij| |x_j|.
struct Residual {
  double worst, scale;
};
Residual residual(SUNMatrix A, N_Vector x, N_Vector b) {
  const sunindextype n = SM_COLUMNS_S(A);
  const double* xs = N_VGetArrayPointer(x);
  std::vector<double> r(N_VGetArrayPointer(b), N_VGetArrayPointer(b) + n), row_scale(r.size(), 0.0);
  for (sunindextype j = 0; j < n; ++j)
    for (sunindextype k = SM_INDEXPTRS_S(A)[j]; k < SM_INDEXPTRS_S(A)[j + 1]; ++k) {
      const auto i = static_cast<std::size_t>(SM_INDEXVALS_S(A)[k]);
      r[i] -= SM_DATA_S(A)[k] * xs[j];
      row_scale[i] += std::abs(SM_DATA_S(A)[k] * xs[j]);
    }
  Residual out{0, 0};
  for (std::size_t i = 0; i < r.size(); ++i) {
    out.worst = std::max(out.worst, std::abs(r[i]));
    out.scale = std::max(out.scale, row_scale[i]);
  }
  return out;
}

// KLU's analysis sets common.structural_rank (from its BTF ordering) and nothing else writes it,
// so a value planted there survives exactly when the analysis is not redone.
TEST(KluAnalysis, KeptAcrossInitialisationsAndRedoneForANewPattern) {
  const Context ctx = make_context();
  const NVector y(N_VNew_Serial(kKluSize, ctx.get())), b(N_VNew_Serial(kKluSize, ctx.get())),
      x(N_VNew_Serial(kKluSize, ctx.get()));
  for (sunindextype i = 0; i < kKluSize; ++i) N_VGetArrayPointer(b.get())[i] = 1.0 + static_cast<double>(i);
  LinearSystem ls = make_linear_system(contact::LinearSolverKind::Klu, y.get(), {}, 3 * kKluSize, ctx.get());
  SUNMatrix A = ls.matrix.get();
  SUNLinearSolver S = ls.solver.get();
  auto& common = static_cast<SUNLinearSolverContent_KLU>(S->content)->common;
  auto solve = [&] {
    ASSERT_EQ(SUNLinSolSetup(S, A), SUNLS_SUCCESS);
    ASSERT_EQ(SUNLinSolSolve(S, A, x.get(), b.get(), 0.0), SUNLS_SUCCESS);
    // A diagonally dominant 6 x 6 system (entries <= 11.5, |x| < 0.75): LU's rounding leaves a
    // residual of order n eps |A| |x| ~ 1e-14; a wrong factorisation leaves order one (0.52 measured).
    EXPECT_LT(residual(A, x.get(), b.get()).worst, 1e-13);
  };
  auto next = [](sunindextype j) { return std::vector<sunindextype>{(j + 1) % kKluSize}; };
  auto previous = [](sunindextype j) { return std::vector<sunindextype>{(j + kKluSize - 1) % kKluSize}; };

  fill(A, next, 0.0);
  ASSERT_EQ(SUNLinSolInitialize(S), SUNLS_SUCCESS);
  solve();
  EXPECT_EQ(common.structural_rank, kKluSize);  // analysed

  common.structural_rank = -7;
  fill(A, next, 2.5);                                // new values, the same pattern
  ASSERT_EQ(SUNLinSolInitialize(S), SUNLS_SUCCESS);  // what a re-initialised integrator does
  solve();
  EXPECT_EQ(common.structural_rank, -7) << "the analysis was redone for the same pattern";

  fill(A, previous, 1.0);  // as many entries, in other rows
  solve();
  EXPECT_EQ(common.structural_rank, kKluSize) << "a new pattern was not analysed";
}

// KLU factorises without row scaling (sundials_linear_solver.cpp: it only steered the threshold
// pivoting and cost 7-10 % of the chain's CPU). Partial pivoting is backward stable without it:
// the Newton matrix of a stiff chain, I - gamma J over (x, v) with gamma k / m = 1e5, so that its
// entries span 1e-3 to 2e5 by row, is solved to a residual of rounding size, n eps |M| |x| with a
// small growth factor (bound 1e-13 relative for n = 100; a wrong factorisation leaves order one).
TEST(KluScaling, FactorisesUnscaledAndSolvesABadlyScaledChainToRounding) {
  constexpr sunindextype balls = 50, n = 2 * balls;
  constexpr double gamma = 1e-3, stiffness = 1e8;  // gamma and k / m
  const Context ctx = make_context();
  const NVector y(N_VNew_Serial(n, ctx.get())), b(N_VNew_Serial(n, ctx.get())),
      x(N_VNew_Serial(n, ctx.get()));
  LinearSystem ls = make_linear_system(contact::LinearSolverKind::Klu, y.get(), {}, 5 * n, ctx.get());
  SUNMatrix A = ls.matrix.get();
  SUNLinearSolver S = ls.solver.get();
  EXPECT_EQ(static_cast<SUNLinearSolverContent_KLU>(S->content)->common.scale, -1);

  // Columns x_j: 1 on the diagonal, gamma k/m (2, -1, -1) in rows v_j, v_{j-1}, v_{j+1} (a chain's
  // Laplacian); columns v_j: -gamma in row x_j, 1 on the diagonal.
  std::vector<std::vector<std::pair<sunindextype, double>>> columns(static_cast<std::size_t>(n));
  for (sunindextype j = 0; j < balls; ++j) {
    auto& cx = columns[static_cast<std::size_t>(j)];
    cx.push_back({j, 1.0});
    if (j > 0) cx.push_back({balls + j - 1, -gamma * stiffness});
    cx.push_back({balls + j, 2 * gamma * stiffness});
    if (j + 1 < balls) cx.push_back({balls + j + 1, -gamma * stiffness});
    columns[static_cast<std::size_t>(balls + j)] = {{j, -gamma}, {balls + j, 1.0}};
  }
  sunindextype k = 0;
  for (sunindextype j = 0; j < n; ++j) {
    SM_INDEXPTRS_S(A)[j] = k;
    for (const auto& [row, value] : columns[static_cast<std::size_t>(j)]) {
      SM_INDEXVALS_S(A)[k] = row;
      SM_DATA_S(A)[k++] = value;
    }
  }
  SM_INDEXPTRS_S(A)[n] = k;
  for (sunindextype i = 0; i < n; ++i) N_VGetArrayPointer(b.get())[i] = std::cos(static_cast<double>(i));

  ASSERT_EQ(SUNLinSolInitialize(S), SUNLS_SUCCESS);
  ASSERT_EQ(SUNLinSolSetup(S, A), SUNLS_SUCCESS);
  ASSERT_EQ(SUNLinSolSolve(S, A, x.get(), b.get(), 0.0), SUNLS_SUCCESS);
  const Residual res = residual(A, x.get(), b.get());
  EXPECT_LT(res.worst / res.scale, 1e-13) << "residual " << res.worst << " against |M||x| " << res.scale;
}

}  // namespace klu_analysis_test
