#include "sundials_linear_solver.hpp"

#include "dense_limit.hpp"
#include "sundials_matrix_ops.hpp"

#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "contact_ode/integrators/status.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace contact::sundials {

namespace {

template <class Handle>
void require(const Handle& h, const char* what, sunindextype n) {
  if (!h)
    throw SolverFailure(Status::SolverError, 0.0,
                        fmt::format("{} returned NULL for n = {} (out of memory?)", what, n));
}

// KLU keeps its symbolic analysis across re-initialisations. CVODE and ARKODE initialise the
// linear solver at the first step after every re-initialisation (a restart at each contact
// switch), and SUNDIALS' KLU then redoes its symbolic analysis (the BTF and COLAMD orderings) and
// a factorisation with pivoting: in the chain's run at N = 1e3, at its start and its 18 restarts,
// 15 % of its instructions. The analysis depends on the pattern alone, which a scene's Jacobian
// keeps (every entry stored whatever the modes), so initialisation keeps it, and setup redoes it
// only where the matrix's pattern differs from the analysed one (compared entry by entry).
// Between re-initialisations SUNDIALS refactors with the pivot order kept as before, and
// factorises afresh when the condition estimate has grown. The analysed pattern lives in KLU's
// `common.user_data`, which only a user ordering function (ordering 3, never set) would read; the
// solver's free deletes it.
struct KluPattern {
  std::vector<sunindextype> pointers, rows;
};

SUNLinearSolverContent_KLU klu_content(SUNLinearSolver S) {
  return static_cast<SUNLinearSolverContent_KLU>(S->content);
}

int initialize_keeping_analysis(SUNLinearSolver S) {
  const SUNLinearSolverContent_KLU c = klu_content(S);
  if (!c->symbolic) c->first_factorize = 1;
  c->last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}

int setup_analysing_new_patterns(SUNLinearSolver S, SUNMatrix A) {
  const SUNLinearSolverContent_KLU c = klu_content(S);
  auto* analysed = static_cast<KluPattern*>(c->common.user_data);
  if (analysed && SUNMatGetID(A) == SUNMATRIX_SPARSE) {
    const sunindextype np = SM_NP_S(A), nz = SM_INDEXPTRS_S(A)[np];
    const sunindextype *pointers = SM_INDEXPTRS_S(A), *rows = SM_INDEXVALS_S(A);
    const bool same =
        std::equal(pointers, pointers + np + 1, analysed->pointers.begin(), analysed->pointers.end()) &&
        std::equal(rows, rows + nz, analysed->rows.begin(), analysed->rows.end());
    if (!same) {
      c->first_factorize = 1;
      analysed->pointers.assign(pointers, pointers + np + 1);
      analysed->rows.assign(rows, rows + nz);
    }
  }
  return SUNLinSolSetup_KLU(S, A);
}

int free_with_pattern(SUNLinearSolver S) {
  if (S && S->content) delete static_cast<KluPattern*>(klu_content(S)->common.user_data);
  return SUNLinSolFree_KLU(S);
}

// KLU scales the rows of every matrix it factorises (by default by each row's largest entry).
// That steers only which pivots its threshold partial pivoting takes (a refactorisation keeps
// them); pivoting by rows is backward stable with or without it. Unscaled, the chain's run at
// N = 1e3 under KLU took 7-10 % less CPU (a pass over every entry at each of its 149 setups).
// Scale -1 also skips KLU's check for duplicate or out-of-range row indices, which the
// Jacobian's compressed storage never has.
void factorise_unscaled(SUNLinearSolver S) { klu_content(S)->common.scale = -1; }

void keep_klu_analysis(SUNLinearSolver S) {
  klu_content(S)->common.user_data = new KluPattern;
  S->ops->free = free_with_pattern;
  S->ops->initialize = initialize_keeping_analysis;
  S->ops->setup = setup_analysing_new_patterns;
}

}  // namespace

LinearSystem make_linear_system(LinearSolverKind kind, N_Vector y, Bandwidth band, long nonzeros,
                                SUNContext ctx) {
  const sunindextype n = N_VGetLength(y);
  LinearSystem ls;
  switch (kind) {
    case LinearSolverKind::Auto:
      throw std::logic_error("make_linear_system: 'auto' is resolved by the caller (has_narrow_band)");
    case LinearSolverKind::Dense: {
      refuse_dense_beyond_limit(static_cast<double>(n), 1, "use the band, klu or gmres linear solver");
      ls.matrix.reset(SUNDenseMatrix(n, n, ctx));
      require(ls.matrix, "SUNDenseMatrix", n);
      ls.solver.reset(SUNLinSol_Dense(y, ls.matrix.get(), ctx));
      require(ls.solver, "SUNLinSol_Dense", n);
      use_compiled_matrix_ops(ls.matrix.get(), ls.solver.get());
      break;
    }
    case LinearSolverKind::Band:
      ls.matrix.reset(SUNBandMatrix(n, band.upper, band.lower, ctx));
      require(ls.matrix, "SUNBandMatrix", n);
      ls.solver.reset(SUNLinSol_Band(y, ls.matrix.get(), ctx));
      require(ls.solver, "SUNLinSol_Band", n);
      use_compiled_matrix_ops(ls.matrix.get(), ls.solver.get());
      break;
    case LinearSolverKind::Klu:
      ls.matrix.reset(SUNSparseMatrix(n, n, std::max(nonzeros, 1L), CSC_MAT, ctx));
      require(ls.matrix, "SUNSparseMatrix", n);
      ls.solver.reset(SUNLinSol_KLU(y, ls.matrix.get(), ctx));
      require(ls.solver, "SUNLinSol_KLU", n);
      use_compiled_matrix_ops(ls.matrix.get(), ls.solver.get());
      keep_klu_analysis(ls.solver.get());
      factorise_unscaled(ls.solver.get());
      break;
    case LinearSolverKind::Gmres:
      ls.solver.reset(SUNLinSol_SPGMR(y, SUN_PREC_NONE, 0, ctx));
      require(ls.solver, "SUNLinSol_SPGMR", n);
      break;
    case LinearSolverKind::GmresBandPreconditioned:
      ls.solver.reset(SUNLinSol_SPGMR(y, SUN_PREC_LEFT, 0, ctx));
      require(ls.solver, "SUNLinSol_SPGMR", n);
      break;
  }
  return ls;
}

bool copy_jacobian(const SparseMatrix& J, SUNMatrix A) {
  switch (SUNMatGetID(A)) {
    case SUNMATRIX_DENSE: {
      SUNMatZero(A);
      const sunindextype ld = SUNDenseMatrix_LData(A) / SUNDenseMatrix_Columns(A);
      sunrealtype* data = SUNDenseMatrix_Data(A);
      for (int j = 0; j < J.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(J, j); it; ++it) data[j * ld + it.row()] = it.value();
      return true;
    }
    case SUNMATRIX_BAND: {
      SUNMatZero(A);
      const sunindextype mu = SUNBandMatrix_UpperBandwidth(A), ml = SUNBandMatrix_LowerBandwidth(A);
      for (int j = 0; j < J.outerSize(); ++j) {
        sunrealtype* col = SUNBandMatrix_Column(A, j);
        for (SparseMatrix::InnerIterator it(J, j); it; ++it) {
          const sunindextype i = it.row();
          if (i - j > ml || j - i > mu) return false;
          SM_COLUMN_ELEMENT_B(col, i, j) = it.value();
        }
      }
      return true;
    }
    case SUNMATRIX_SPARSE: {
      if (SUNSparseMatrix_NNZ(A) < J.nonZeros() &&
          SUNSparseMatrix_Reallocate(A, static_cast<sunindextype>(J.nonZeros())) != 0)
        return false;
      sunindextype* colptr = SUNSparseMatrix_IndexPointers(A);
      sunindextype* rows = SUNSparseMatrix_IndexValues(A);
      sunrealtype* data = SUNSparseMatrix_Data(A);
      const int* outer = J.outerIndexPtr();
      for (int j = 0; j <= J.outerSize(); ++j) colptr[j] = J.isCompressed() ? outer[j] : 0;
      if (!J.isCompressed()) return false;
      for (long k = 0; k < J.nonZeros(); ++k) {
        rows[k] = J.innerIndexPtr()[k];
        data[k] = J.valuePtr()[k];
      }
      return true;
    }
    default:
      return false;
  }
}

void multiply(const SparseMatrix& J, N_Vector v, N_Vector Jv) {
  const auto n = static_cast<Eigen::Index>(N_VGetLength(v));
  Eigen::Map<Vector> out(N_VGetArrayPointer(Jv), n);
  out.noalias() = J * Eigen::Map<const Vector>(N_VGetArrayPointer(v), n);
}

}  // namespace contact::sundials
