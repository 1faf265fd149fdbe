#include "sundials_matrix_ops.hpp"

#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace contact::sundials {

namespace {

// The pivots and the last flag of a dense or band solver (Content: its content's pointer type).
struct Pivots {
  sunindextype* p;
  sunindextype& last_flag;
};
template <class Content>
Pivots pivots(SUNLinearSolver S) {
  auto* c = static_cast<Content>(S->content);
  return {c->pivots, c->last_flag};
}
// Records a setup's or solve's flag: 0, a SUNLS_ error (< 0), or a factorisation's zero pivot (k + 1 > 0).
int finish(sunindextype& last_flag, sunindextype flag) {
  last_flag = flag;
  return flag > 0 ? SUNLS_LUFACT_FAIL : static_cast<int>(flag);
}

bool is_dense(SUNMatrix A) { return A && SUNMatGetID(A) == SUNMATRIX_DENSE; }
bool is_band(SUNMatrix A) { return A && SUNMatGetID(A) == SUNMATRIX_BAND; }

// A = 0 over the whole storage (both contents hold `data` and its length `ldata`).
template <class Content>
int zero(SUNMatrix A) {
  const auto* c = static_cast<Content>(A->content);
  std::fill_n(c->data, c->ldata, 0.0);
  return SUNMAT_SUCCESS;
}

// ---- dense: column-major, cols[j] the j-th column ----

void install_dense(SUNMatrix A);

SUNMatrix clone_dense(SUNMatrix A) {
  SUNMatrix B = SUNDenseMatrix(SM_ROWS_D(A), SM_COLUMNS_D(A), A->sunctx);
  if (B) install_dense(B);
  return B;
}

int copy_dense(SUNMatrix A, SUNMatrix B) {  // B = A
  if (!is_dense(B) || SM_ROWS_D(A) != SM_ROWS_D(B) || SM_COLUMNS_D(A) != SM_COLUMNS_D(B))
    return SUNMAT_ILL_INPUT;
  std::copy_n(SM_DATA_D(A), SM_LDATA_D(A), SM_DATA_D(B));
  return SUNMAT_SUCCESS;
}

int scale_add_identity_dense(sunrealtype c, SUNMatrix A) {  // A = c A + I: each product, then the one
  const sunindextype m = SM_ROWS_D(A), n = SM_COLUMNS_D(A);
  sunrealtype* a = SM_DATA_D(A);
  for (sunindextype k = 0; k < m * n; ++k) a[k] *= c;
  for (sunindextype j = 0; j < std::min(m, n); ++j) a[j * m + j] += 1.0;
  return SUNMAT_SUCCESS;
}

// P A = L U in place (L's multipliers below the diagonal); 0, or k + 1 where the k-th pivot is zero.
sunindextype factor_dense(sunrealtype** a, sunindextype m, sunindextype n, sunindextype* p) {
  for (sunindextype k = 0; k < n; ++k) {
    sunrealtype* col_k = a[k];
    sunindextype l = k;
    for (sunindextype i = k + 1; i < m; ++i)
      if (std::abs(col_k[i]) > std::abs(col_k[l])) l = i;
    p[k] = l;
    if (col_k[l] == 0.0) return k + 1;
    if (l != k)
      for (sunindextype j = 0; j < n; ++j) std::swap(a[j][l], a[j][k]);
    const sunrealtype mult = 1.0 / col_k[k];
    for (sunindextype i = k + 1; i < m; ++i) col_k[i] *= mult;
    for (sunindextype j = k + 1; j < n; ++j) {
      sunrealtype* col_j = a[j];
      const sunrealtype a_kj = col_j[k];
      if (a_kj != 0.0)
        for (sunindextype i = k + 1; i < m; ++i) col_j[i] -= a_kj * col_k[i];
    }
  }
  return 0;
}

// b = A^-1 b from factor_dense's L, U and pivots.
void substitute_dense(sunrealtype* const* a, sunindextype n, const sunindextype* p, sunrealtype* b) {
  for (sunindextype k = 0; k < n; ++k)
    if (p[k] != k) std::swap(b[k], b[p[k]]);
  for (sunindextype k = 0; k + 1 < n; ++k) {
    const sunrealtype* col_k = a[k];
    const sunrealtype bk = b[k];
    for (sunindextype i = k + 1; i < n; ++i) b[i] -= col_k[i] * bk;
  }
  for (sunindextype k = n - 1; k > 0; --k) {
    const sunrealtype* col_k = a[k];
    b[k] /= col_k[k];
    const sunrealtype bk = b[k];
    for (sunindextype i = 0; i < k; ++i) b[i] -= col_k[i] * bk;
  }
  b[0] /= a[0][0];
}

int setup_dense(SUNLinearSolver S, SUNMatrix A) {
  auto [p, last_flag] = pivots<SUNLinearSolverContent_Dense>(S);
  if (!is_dense(A)) return finish(last_flag, SUNLS_ILL_INPUT);
  return finish(last_flag, factor_dense(SM_COLS_D(A), SM_ROWS_D(A), SM_COLUMNS_D(A), p));
}

int solve_dense(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, sunrealtype /*tol*/) {
  auto [p, last_flag] = pivots<SUNLinearSolverContent_Dense>(S);
  if (!is_dense(A) || !x || !b) return finish(last_flag, SUNLS_MEM_NULL);
  N_VScale(1.0, b, x);
  substitute_dense(SM_COLS_D(A), SM_ROWS_D(A), p, N_VGetArrayPointer(x));
  return finish(last_flag, SUNLS_SUCCESS);
}

void install_dense(SUNMatrix A) {
  A->ops->clone = clone_dense;
  A->ops->zero = zero<SUNMatrixContent_Dense>;
  A->ops->copy = copy_dense;
  A->ops->scaleaddi = scale_add_identity_dense;
}

// ---- band: cols[j] a column's storage, its diagonal at cols[j][s_mu], row i at cols[j][i - j + s_mu];
// the s_mu - mu rows above the band are the factorisation's fill-in ----

void install_band(SUNMatrix A);

SUNMatrix clone_band(SUNMatrix A) {
  SUNMatrix B =
      SUNBandMatrixStorage(SM_COLUMNS_B(A), SM_UBAND_B(A), SM_LBAND_B(A), SM_SUBAND_B(A), A->sunctx);
  if (B) install_band(B);
  return B;
}

int copy_band(SUNMatrix A, SUNMatrix B) {  // B = A
  if (!is_band(B) || SM_ROWS_B(A) != SM_ROWS_B(B) || SM_COLUMNS_B(A) != SM_COLUMNS_B(B))
    return SUNMAT_ILL_INPUT;
  if (SM_UBAND_B(A) > SM_UBAND_B(B) || SM_LBAND_B(A) > SM_LBAND_B(B))
    return SUNMatCopy_Band(A, B);  // B's storage grows: the library's reallocation
  zero<SUNMatrixContent_Band>(B);
  const sunindextype mu = SM_UBAND_B(A), width = mu + SM_LBAND_B(A) + 1;
  for (sunindextype j = 0; j < SM_COLUMNS_B(B); ++j)
    std::copy_n(SM_COLUMN_B(A, j) - mu, width, SM_COLUMN_B(B, j) - mu);
  return SUNMAT_SUCCESS;
}

int scale_add_identity_band(sunrealtype c, SUNMatrix A) {  // A = c A + I on the band
  const sunindextype mu = SM_UBAND_B(A), width = mu + SM_LBAND_B(A) + 1;
  for (sunindextype j = 0; j < SM_COLUMNS_B(A); ++j) {
    sunrealtype* col = SM_COLUMN_B(A, j) - mu;
    for (sunindextype i = 0; i < width; ++i) col[i] *= c;
    col[mu] += 1.0;
  }
  return SUNMAT_SUCCESS;
}

// P A = L U in the band storage; L's multipliers are stored negated (-a_ik / a_kk), as the library does.
sunindextype factor_band(sunrealtype** a, sunindextype n, sunindextype mu, sunindextype ml, sunindextype smu,
                         sunindextype* p) {
  if (smu > mu)
    for (sunindextype c = 0; c < n; ++c) std::fill_n(a[c], smu - mu, 0.0);
  for (sunindextype k = 0; k + 1 < n; ++k) {
    sunrealtype* col_k = a[k];
    sunrealtype* diag_k = col_k + smu;
    sunrealtype* below = diag_k + 1;  // rows k + 1 .. last_row
    const sunindextype below_count = std::min(n - 1, k + ml) - k;
    sunindextype l = k;
    sunrealtype largest = std::abs(*diag_k);
    for (sunindextype i = 0; i < below_count; ++i)
      if (std::abs(below[i]) > largest) {
        l = k + 1 + i;
        largest = std::abs(below[i]);
      }
    p[k] = l;
    if (col_k[l - k + smu] == 0.0) return k + 1;
    const bool swap = l != k;
    if (swap) std::swap(col_k[l - k + smu], *diag_k);
    const sunrealtype mult = -1.0 / *diag_k;
    for (sunindextype i = 0; i < below_count; ++i) below[i] *= mult;
    const sunindextype last_col = std::min(k + smu, n - 1);
    for (sunindextype j = k + 1; j <= last_col; ++j) {
      sunrealtype* col_j = a[j];
      const sunindextype at_l = l - j + smu, at_k = k - j + smu;
      const sunrealtype a_kj = col_j[at_l];
      if (swap) {
        col_j[at_l] = col_j[at_k];
        col_j[at_k] = a_kj;
      }
      if (a_kj != 0.0) {
        sunrealtype* rows = col_j + at_k + 1;
        for (sunindextype i = 0; i < below_count; ++i) rows[i] += a_kj * below[i];
      }
    }
  }
  p[n - 1] = n - 1;
  return a[n - 1][smu] == 0.0 ? n : 0;
}

// b = A^-1 b from factor_band's L, U and pivots. Each substitution is a chain, row after row: the
// next row's value is this row's last update. That update is kept in a register (`next`) as well as
// stored, so the chain does not wait on a store and a reload each row: a solve of the chain's
// 2001-row band 9 % faster, the chain's band run at N = 1e3 (30 % of it in these solves) 3 %. The
// operations and their order are the library's.
void substitute_band(sunrealtype* const* a, sunindextype n, sunindextype smu, sunindextype ml,
                     const sunindextype* p, sunrealtype* b) {
  sunrealtype next = n > 0 ? b[0] : 0.0;  // b[k] as the row before left it
  for (sunindextype k = 0; k + 1 < n; ++k) {
    const sunindextype l = p[k];
    const sunrealtype mult = l == k ? next : b[l];
    if (l != k) {
      b[l] = b[k];
      b[k] = mult;
    }
    const sunrealtype* diag_k = a[k] + smu;
    const sunindextype last_row = std::min(n - 1, k + ml);
    next = b[k + 1];
    if (last_row > k) {
      next += mult * diag_k[1];
      b[k + 1] = next;
    }
    for (sunindextype i = k + 2; i <= last_row; ++i) b[i] += mult * diag_k[i - k];
  }
  next = n > 0 ? b[n - 1] : 0.0;
  for (sunindextype k = n - 1; k >= 0; --k) {
    const sunrealtype* diag_k = a[k] + smu;
    const sunrealtype x = next / *diag_k;
    b[k] = x;
    const sunrealtype mult = -x;
    const sunindextype first_row = std::max<sunindextype>(0, k - smu);
    for (sunindextype i = first_row; i + 1 < k; ++i) b[i] += mult * diag_k[i - k];
    if (k > 0) {
      next = b[k - 1];
      if (first_row < k) {
        next += mult * diag_k[-1];
        b[k - 1] = next;
      }
    }
  }
}

int setup_band(SUNLinearSolver S, SUNMatrix A) {
  auto [p, last_flag] = pivots<SUNLinearSolverContent_Band>(S);
  if (!is_band(A)) return finish(last_flag, SUNLS_ILL_INPUT);
  const sunindextype n = SM_COLUMNS_B(A), mu = SM_UBAND_B(A), ml = SM_LBAND_B(A), smu = SM_SUBAND_B(A);
  if (smu < std::min(n - 1, mu + ml)) return finish(last_flag, SUNLS_MEM_FAIL);  // no room for fill-in
  return finish(last_flag, factor_band(SM_COLS_B(A), n, mu, ml, smu, p));
}

int solve_band(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, sunrealtype /*tol*/) {
  auto [p, last_flag] = pivots<SUNLinearSolverContent_Band>(S);
  if (!is_band(A) || !x || !b) return finish(last_flag, SUNLS_MEM_NULL);
  N_VScale(1.0, b, x);
  substitute_band(SM_COLS_B(A), SM_COLUMNS_B(A), SM_SUBAND_B(A), SM_LBAND_B(A), p, N_VGetArrayPointer(x));
  return finish(last_flag, SUNLS_SUCCESS);
}

void install_band(SUNMatrix A) {
  A->ops->clone = clone_band;
  A->ops->zero = zero<SUNMatrixContent_Band>;
  A->ops->copy = copy_band;
  A->ops->scaleaddi = scale_add_identity_band;
}

// ---- sparse (KLU's): values and indices over the storage's capacity NNZ, NP + 1 pointers ----

bool is_sparse(SUNMatrix A) { return A && SUNMatGetID(A) == SUNMATRIX_SPARSE; }

void install_sparse(SUNMatrix A);

SUNMatrix clone_sparse(SUNMatrix A) {
  SUNMatrix B = SUNSparseMatrix(SM_ROWS_S(A), SM_COLUMNS_S(A), SM_NNZ_S(A), SM_SPARSETYPE_S(A), A->sunctx);
  if (B) install_sparse(B);
  return B;
}

int zero_sparse(SUNMatrix A) {  // every stored value and index, and the pointers
  std::fill_n(SM_DATA_S(A), SM_NNZ_S(A), 0.0);
  std::fill_n(SM_INDEXVALS_S(A), SM_NNZ_S(A), sunindextype{0});
  std::fill_n(SM_INDEXPTRS_S(A), SM_NP_S(A) + 1, sunindextype{0});
  return SUNMAT_SUCCESS;
}

// B = A, zeros over the rest of B's storage (the library zeroes B, then copies).
int copy_sparse(SUNMatrix A, SUNMatrix B) {
  if (!is_sparse(B) || SM_ROWS_S(A) != SM_ROWS_S(B) || SM_COLUMNS_S(A) != SM_COLUMNS_S(B) ||
      SM_SPARSETYPE_S(A) != SM_SPARSETYPE_S(B))
    return SUNMAT_ILL_INPUT;
  const sunindextype np = SM_NP_S(A), nz = SM_INDEXPTRS_S(A)[np], capacity = SM_NNZ_S(B);
  if (capacity < nz) return SUNMatCopy_Sparse(A, B);  // B's storage grows: the library's reallocation
  std::copy_n(SM_DATA_S(A), nz, SM_DATA_S(B));
  std::fill(SM_DATA_S(B) + nz, SM_DATA_S(B) + capacity, 0.0);
  std::copy_n(SM_INDEXVALS_S(A), nz, SM_INDEXVALS_S(B));
  std::fill(SM_INDEXVALS_S(B) + nz, SM_INDEXVALS_S(B) + capacity, sunindextype{0});
  std::copy_n(SM_INDEXPTRS_S(A), np + 1, SM_INDEXPTRS_S(B));
  return SUNMAT_SUCCESS;
}

// A = c A + I, in place where every diagonal entry is stored (the project's Jacobians store theirs),
// as the library does then: 1 + c a on the diagonal, c a elsewhere. Entries to insert: the library's.
int scale_add_identity_sparse(sunrealtype c, SUNMatrix A) {
  const sunindextype n = std::min(SM_ROWS_S(A), SM_COLUMNS_S(A));
  const sunindextype* p = SM_INDEXPTRS_S(A);
  const sunindextype* index = SM_INDEXVALS_S(A);
  sunrealtype* a = SM_DATA_S(A);
  for (sunindextype j = 0; j < n; ++j)
    if (std::find(index + p[j], index + p[j + 1], j) == index + p[j + 1]) return SUNMatScaleAddI_Sparse(c, A);
  for (sunindextype j = 0; j < n; ++j)
    for (sunindextype k = p[j]; k < p[j + 1]; ++k) a[k] = index[k] == j ? 1.0 + c * a[k] : c * a[k];
  return SUNMAT_SUCCESS;
}

void install_sparse(SUNMatrix A) {
  A->ops->clone = clone_sparse;
  A->ops->zero = zero_sparse;
  A->ops->copy = copy_sparse;
  A->ops->scaleaddi = scale_add_identity_sparse;
}

}  // namespace

void use_compiled_matrix_ops(SUNMatrix A, SUNLinearSolver solver) {
  const SUNLinearSolver_ID id = solver ? SUNLinSolGetID(solver) : SUNLINEARSOLVER_CUSTOM;
  if (is_dense(A) && id == SUNLINEARSOLVER_DENSE) {
    install_dense(A);
    solver->ops->setup = setup_dense;
    solver->ops->solve = solve_dense;
  } else if (is_band(A) && id == SUNLINEARSOLVER_BAND) {
    install_band(A);
    solver->ops->setup = setup_band;
    solver->ops->solve = solve_band;
  } else if (is_sparse(A) && id == SUNLINEARSOLVER_KLU) {
    install_sparse(A);  // KLU itself is SuiteSparse's optimised build
  } else {
    throw std::invalid_argument(
        "use_compiled_matrix_ops: a dense, band or sparse matrix with its own solver");
  }
}

}  // namespace contact::sundials
