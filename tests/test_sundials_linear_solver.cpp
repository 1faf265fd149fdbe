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

// max |A x - b| for the matrix in A (CSC).
double residual(SUNMatrix A, N_Vector x, N_Vector b) {
  std::vector<double> r(N_VGetArrayPointer(b), N_VGetArrayPointer(b) + kKluSize);
  for (sunindextype j = 0; j < kKluSize; ++j)
    for (sunindextype k = SM_INDEXPTRS_S(A)[j]; k < SM_INDEXPTRS_S(A)[j + 1]; ++k)
      r[static_cast<std::size_t>(SM_INDEXVALS_S(A)[k])] -= SM_DATA_S(A)[k] * N_VGetArrayPointer(x)[j];
  double worst = 0;
  for (double e : r) worst = std::max(worst, std::abs(e));
  return worst;
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
    EXPECT_LT(residual(A, x.get(), b.get()), 1e-13);
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

}  // namespace klu_analysis_test
