// The compiled dense, band and sparse matrix operations and the dense and band LU solvers
// (integrators/sundials_matrix_ops.hpp)
// stand in for the library's -O0 ones inside CVODE and ARKODE; they must give the library's
// results bit for bit, pivots, zero pivots and fill-in included, or the study's numbers would
// change with the speed-up. Each case runs the library's pair and the compiled pair on the same
// matrix and compares the factors, the pivots, the solutions and the flags.
#include "sundials_handles.hpp"
#include "sundials_matrix_ops.hpp"

#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace {

using contact::sundials::Context;
using contact::sundials::LinearSolver;
using contact::sundials::make_context;
using contact::sundials::NVector;
using contact::sundials::use_compiled_matrix_ops;
using SunMatrix = contact::sundials::Matrix;  // not contact::Matrix, which other test files bring in

constexpr sunindextype kSize = 9;

bool same(const sunrealtype* a, const sunrealtype* b, sunindextype n) {  // bitwise
  return std::memcmp(a, b, static_cast<std::size_t>(n) * sizeof(sunrealtype)) == 0;
}

// A matrix and its solver, with the library's operations or the compiled ones.
struct Pair {
  SunMatrix A;
  LinearSolver solver;
};

class MatrixOps : public ::testing::Test {
 protected:
  // A dense matrix: entries in [-3, 3] (rows swap as the largest magnitude moves), `shape` edits it.
  Pair dense(bool compiled, const std::function<void(sunrealtype** cols)>& shape = {}) const {
    Pair p{SunMatrix(SUNDenseMatrix(kSize, kSize, ctx_.get())), {}};
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (sunindextype k = 0; k < kSize * kSize; ++k) SM_DATA_D(p.A.get())[k] = u(rng);
    if (shape) shape(SM_COLS_D(p.A.get()));
    p.solver.reset(SUNLinSol_Dense(y_.get(), p.A.get(), ctx_.get()));
    if (compiled) use_compiled_matrix_ops(p.A.get(), p.solver.get());
    return p;
  }
  // A band matrix (upper bandwidth mu, lower ml, stored upper smu), its band entries random.
  Pair band(bool compiled, sunindextype mu, sunindextype ml, sunindextype smu,
            const std::function<void(SUNMatrix)>& shape = {}) const {
    Pair p{SunMatrix(SUNBandMatrixStorage(kSize, mu, ml, smu, ctx_.get())), {}};
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (sunindextype k = 0; k < SM_LDATA_B(p.A.get()); ++k) SM_DATA_B(p.A.get())[k] = u(rng);
    if (shape) shape(p.A.get());
    p.solver.reset(SUNLinSol_Band(y_.get(), p.A.get(), ctx_.get()));
    if (compiled) use_compiled_matrix_ops(p.A.get(), p.solver.get());
    return p;
  }
  static const sunrealtype* data(const Pair& p) {
    return SUNMatGetID(p.A.get()) == SUNMATRIX_DENSE ? SM_DATA_D(p.A.get()) : SM_DATA_B(p.A.get());
  }
  static sunindextype length(const Pair& p) {
    return SUNMatGetID(p.A.get()) == SUNMATRIX_DENSE ? SM_LDATA_D(p.A.get()) : SM_LDATA_B(p.A.get());
  }
  static const sunindextype* pivots(const Pair& p) {
    if (SUNLinSolGetID(p.solver.get()) == SUNLINEARSOLVER_DENSE)
      return static_cast<SUNLinearSolverContent_Dense>(p.solver->content)->pivots;
    return static_cast<SUNLinearSolverContent_Band>(p.solver->content)->pivots;
  }
  // Factors and solves with both pairs; everything must agree bitwise.
  void expect_same_solve(Pair& library, Pair& compiled, const char* what) const {
    const int lflag = SUNLinSolSetup(library.solver.get(), library.A.get());
    const int cflag = SUNLinSolSetup(compiled.solver.get(), compiled.A.get());
    EXPECT_EQ(lflag, cflag) << what;
    EXPECT_EQ(SUNLinSolLastFlag(library.solver.get()), SUNLinSolLastFlag(compiled.solver.get())) << what;
    EXPECT_TRUE(same(data(library), data(compiled), length(library))) << what << ": the factors";
    if (lflag != SUNLS_SUCCESS) return;  // a zero pivot: the solve is not asked for
    EXPECT_EQ(std::vector<sunindextype>(pivots(library), pivots(library) + kSize),
              std::vector<sunindextype>(pivots(compiled), pivots(compiled) + kSize))
        << what;
    NVector b(N_VNew_Serial(kSize, ctx_.get())), lx(N_VNew_Serial(kSize, ctx_.get())),
        cx(N_VNew_Serial(kSize, ctx_.get()));
    for (sunindextype i = 0; i < kSize; ++i) NV_Ith_S(b.get(), i) = 0.5 - 0.3 * static_cast<double>(i);
    EXPECT_EQ(SUNLinSolSolve(library.solver.get(), library.A.get(), lx.get(), b.get(), 0.0), SUNLS_SUCCESS);
    EXPECT_EQ(SUNLinSolSolve(compiled.solver.get(), compiled.A.get(), cx.get(), b.get(), 0.0), SUNLS_SUCCESS);
    EXPECT_TRUE(same(NV_DATA_S(lx.get()), NV_DATA_S(cx.get()), kSize)) << what << ": the solution";
  }

  Context ctx_ = make_context();
  NVector y_{N_VNew_Serial(kSize, ctx_.get())};
};

TEST_F(MatrixOps, DenseFactorAndSolveMatchTheLibrary) {
  Pair l = dense(false), c = dense(true);
  expect_same_solve(l, c, "random");
  // A zero in the pivot row skips that column's update (the library's a_kj != 0 test)
  const auto sparse_row = [](sunrealtype** cols) {
    for (sunindextype j = 1; j < kSize; j += 2) cols[j][0] = 0.0;
    cols[0][0] = 10.0;  // row 0 stays the first pivot
  };
  Pair ls = dense(false, sparse_row), cs = dense(true, sparse_row);
  expect_same_solve(ls, cs, "zero multipliers");
  // A zero column: the same failed pivot (k + 1) and flag
  const auto singular = [](sunrealtype** cols) {
    for (sunindextype i = 0; i < kSize; ++i) cols[4][i] = 0.0;
  };
  Pair lz = dense(false, singular), cz = dense(true, singular);
  expect_same_solve(lz, cz, "singular");
  EXPECT_EQ(SUNLinSolLastFlag(cz.solver.get()), 5);
}

TEST_F(MatrixOps, DenseMatrixOperationsMatchTheLibrary) {
  Pair l = dense(false), c = dense(true);
  ASSERT_EQ(SUNMatScaleAddI(-0.37, l.A.get()), 0);
  ASSERT_EQ(SUNMatScaleAddI(-0.37, c.A.get()), 0);
  EXPECT_TRUE(same(data(l), data(c), length(l))) << "c A + I";
  SunMatrix lcopy(SUNMatClone(l.A.get())), ccopy(SUNMatClone(c.A.get()));
  ASSERT_TRUE(lcopy && ccopy);
  EXPECT_EQ(ccopy->ops->scaleaddi, c.A->ops->scaleaddi);  // CVODE's saved Jacobian is a clone
  EXPECT_NE(ccopy->ops->scaleaddi, SUNMatScaleAddI_Dense);
  ASSERT_EQ(SUNMatCopy(l.A.get(), lcopy.get()), 0);
  ASSERT_EQ(SUNMatCopy(c.A.get(), ccopy.get()), 0);
  EXPECT_TRUE(same(SM_DATA_D(lcopy.get()), SM_DATA_D(ccopy.get()), kSize * kSize)) << "copy";
  ASSERT_EQ(SUNMatZero(ccopy.get()), 0);
  for (sunindextype k = 0; k < kSize * kSize; ++k) EXPECT_EQ(SM_DATA_D(ccopy.get())[k], 0.0);
  SunMatrix other(SUNDenseMatrix(kSize - 1, kSize - 1, ctx_.get()));
  EXPECT_NE(SUNMatCopy(c.A.get(), other.get()), 0) << "a copy between shapes is refused";
}

TEST_F(MatrixOps, BandFactorAndSolveMatchTheLibrary) {
  for (const auto& [mu, ml] : {std::pair<sunindextype, sunindextype>{2, 3}, {1, 1}, {0, 2}, {3, 0}}) {
    const sunindextype smu = std::min(kSize - 1, mu + ml);
    Pair l = band(false, mu, ml, smu), c = band(true, mu, ml, smu);
    expect_same_solve(l, c, "random band");
    // Stored upper bandwidth beyond what fill-in needs: the extra rows are zeroed first
    Pair lw = band(false, mu, ml, smu + 2), cw = band(true, mu, ml, smu + 2);
    expect_same_solve(lw, cw, "wide storage");
  }
  const auto zero_column = [](SUNMatrix A) {
    for (sunindextype i = -SM_UBAND_B(A); i <= SM_LBAND_B(A); ++i) SM_COLUMN_B(A, 6)[i] = 0.0;
  };
  Pair lz = band(false, 2, 3, 5, zero_column), cz = band(true, 2, 3, 5, zero_column);
  expect_same_solve(lz, cz, "singular band");
  EXPECT_GT(SUNLinSolLastFlag(cz.solver.get()), 0);
  // A matrix stored without room for fill-in: refused with the library's flag
  Pair l = band(false, 2, 3, 5), c = band(true, 2, 3, 5);
  SunMatrix narrow(SUNBandMatrixStorage(kSize, 2, 3, 2, ctx_.get()));
  const int refused = SUNLinSolSetup(l.solver.get(), narrow.get());
  EXPECT_NE(refused, SUNLS_SUCCESS);
  EXPECT_EQ(SUNLinSolSetup(c.solver.get(), narrow.get()), refused);
  EXPECT_EQ(SUNLinSolLastFlag(c.solver.get()), SUNLinSolLastFlag(l.solver.get()));
}

TEST_F(MatrixOps, BandMatrixOperationsMatchTheLibrary) {
  Pair l = band(false, 2, 3, 5), c = band(true, 2, 3, 5);
  ASSERT_EQ(SUNMatScaleAddI(0.61, l.A.get()), 0);
  ASSERT_EQ(SUNMatScaleAddI(0.61, c.A.get()), 0);
  EXPECT_TRUE(same(data(l), data(c), length(l))) << "c A + I";
  SunMatrix lcopy(SUNMatClone(l.A.get())), ccopy(SUNMatClone(c.A.get()));
  ASSERT_TRUE(lcopy && ccopy);
  EXPECT_EQ(ccopy->ops->copy, c.A->ops->copy);
  EXPECT_NE(ccopy->ops->copy, SUNMatCopy_Band);
  std::fill_n(SM_DATA_B(lcopy.get()), SM_LDATA_B(lcopy.get()), 7.0);  // copy clears what it does not set
  std::fill_n(SM_DATA_B(ccopy.get()), SM_LDATA_B(ccopy.get()), 7.0);
  ASSERT_EQ(SUNMatCopy(l.A.get(), lcopy.get()), 0);
  ASSERT_EQ(SUNMatCopy(c.A.get(), ccopy.get()), 0);
  EXPECT_TRUE(same(SM_DATA_B(lcopy.get()), SM_DATA_B(ccopy.get()), SM_LDATA_B(lcopy.get()))) << "copy";
  // Into a narrower band: the target's storage grows, as the library's does
  SunMatrix lnarrow(SUNBandMatrixStorage(kSize, 1, 1, 2, ctx_.get())),
      cnarrow(SUNBandMatrixStorage(kSize, 1, 1, 2, ctx_.get()));
  ASSERT_EQ(SUNMatCopy(l.A.get(), lnarrow.get()), 0);
  ASSERT_EQ(SUNMatCopy(c.A.get(), cnarrow.get()), 0);
  ASSERT_EQ(SM_LDATA_B(lnarrow.get()), SM_LDATA_B(cnarrow.get()));
  EXPECT_TRUE(same(SM_DATA_B(lnarrow.get()), SM_DATA_B(cnarrow.get()), SM_LDATA_B(lnarrow.get())))
      << "copy into a narrower band";
}

// A sparse (CSC) matrix with KLU: columns j hold rows j - 2, j and j + 1 (random values), every
// diagonal entry stored unless `without` names the column that lacks it.
Pair sparse(const Context& ctx, N_Vector y, bool compiled, sunindextype without = -1) {
  Pair p{SunMatrix(SUNSparseMatrix(kSize, kSize, 4 * kSize, CSC_MAT, ctx.get())), {}};
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  sunindextype* ptr = SM_INDEXPTRS_S(p.A.get());
  sunindextype nz = 0;
  for (sunindextype j = 0; j < kSize; ++j) {
    ptr[j] = nz;
    for (sunindextype i : {j - 2, j, j + 1})
      if (i >= 0 && i < kSize && !(i == j && j == without)) {
        SM_INDEXVALS_S(p.A.get())[nz] = i;
        SM_DATA_S(p.A.get())[nz++] = u(rng);
      }
  }
  ptr[kSize] = nz;
  p.solver.reset(SUNLinSol_KLU(y, p.A.get(), ctx.get()));
  if (compiled) use_compiled_matrix_ops(p.A.get(), p.solver.get());
  return p;
}

// Storage, pointers, indices and values (over the whole capacity), bitwise.
bool same_sparse(SUNMatrix a, SUNMatrix b) {
  const sunindextype capacity = SM_NNZ_S(a), np = SM_NP_S(a);
  return capacity == SM_NNZ_S(b) && np == SM_NP_S(b) &&
         std::equal(SM_INDEXPTRS_S(a), SM_INDEXPTRS_S(a) + np + 1, SM_INDEXPTRS_S(b)) &&
         std::equal(SM_INDEXVALS_S(a), SM_INDEXVALS_S(a) + capacity, SM_INDEXVALS_S(b)) &&
         same(SM_DATA_S(a), SM_DATA_S(b), capacity);
}

// KLU factors and solves with SuiteSparse's own (optimised) build, so only the sparse matrix's
// operations are compiled: clone, zero, copy and c A + I, the last with every diagonal entry stored
// (a missing one, to be inserted, is left to the library).
TEST_F(MatrixOps, SparseMatrixOperationsMatchTheLibrary) {
  for (sunindextype without : {-1, 4}) {
    Pair l = sparse(ctx_, y_.get(), false, without), c = sparse(ctx_, y_.get(), true, without);
    ASSERT_EQ(SUNMatScaleAddI(0.61, l.A.get()), 0);
    ASSERT_EQ(SUNMatScaleAddI(0.61, c.A.get()), 0);
    EXPECT_TRUE(same_sparse(l.A.get(), c.A.get())) << "c A + I, without diagonal entry " << without;
  }
  Pair l = sparse(ctx_, y_.get(), false), c = sparse(ctx_, y_.get(), true);
  SunMatrix lcopy(SUNMatClone(l.A.get())), ccopy(SUNMatClone(c.A.get()));
  ASSERT_TRUE(lcopy && ccopy);
  EXPECT_EQ(ccopy->ops->copy, c.A->ops->copy);
  EXPECT_NE(ccopy->ops->copy, SUNMatCopy_Sparse);
  for (SUNMatrix m : {lcopy.get(), ccopy.get()}) {  // copy clears what it does not set
    std::fill_n(SM_DATA_S(m), SM_NNZ_S(m), 7.0);
    std::fill_n(SM_INDEXVALS_S(m), SM_NNZ_S(m), sunindextype{3});
  }
  ASSERT_EQ(SUNMatCopy(l.A.get(), lcopy.get()), 0);
  ASSERT_EQ(SUNMatCopy(c.A.get(), ccopy.get()), 0);
  EXPECT_TRUE(same_sparse(lcopy.get(), ccopy.get())) << "copy";
  // Into less storage than the entries: the target grows, as the library's does.
  SunMatrix lsmall(SUNSparseMatrix(kSize, kSize, 2, CSC_MAT, ctx_.get())),
      csmall(SUNSparseMatrix(kSize, kSize, 2, CSC_MAT, ctx_.get()));
  ASSERT_EQ(SUNMatCopy(l.A.get(), lsmall.get()), 0);
  ASSERT_EQ(SUNMatCopy(c.A.get(), csmall.get()), 0);
  EXPECT_TRUE(same_sparse(lsmall.get(), csmall.get())) << "copy into less storage";
  ASSERT_EQ(SUNMatZero(l.A.get()), 0);
  ASSERT_EQ(SUNMatZero(c.A.get()), 0);
  EXPECT_TRUE(same_sparse(l.A.get(), c.A.get())) << "zero";
}

TEST_F(MatrixOps, ASolverOfAnotherKindIsRefused) {
  SunMatrix A(SUNDenseMatrix(kSize, kSize, ctx_.get()));
  SunMatrix B(SUNBandMatrix(kSize, 1, 1, ctx_.get()));
  LinearSolver band_solver(SUNLinSol_Band(y_.get(), B.get(), ctx_.get()));
  EXPECT_THROW(use_compiled_matrix_ops(A.get(), band_solver.get()), std::invalid_argument);
  EXPECT_THROW(use_compiled_matrix_ops(A.get(), nullptr), std::invalid_argument);
}

}  // namespace
