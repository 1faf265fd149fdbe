#pragma once
// The dense, band and sparse matrices and the dense and band LU solvers, compiled here for the reason the
// vectors are (sundials_vector_ops.hpp): Debian 12's SUNDIALS builds them without optimisation. A small
// implicit solve (P1 under CVODE BDF, a 3 x 3 Newton matrix) spent 14 % of its time (perf) in
// their copy, scale-and-add-identity, factorisation and triangular solves, the chain's band solve
// two thirds; compiled, P1 takes 9 % fewer instructions, the chain's dense solve of 1000 balls
// 4.0 s instead of 13.2 s and its band solve 67 ms instead of 79. Each operation is the library's
// algorithm with its floating-point operations in the same order (LU with partial pivoting, the
// first row of largest magnitude as the pivot, an update skipped where its multiplier is zero), so
// results are bitwise those of the library; the cases left to the library are those that reallocate
// (a band copy into a narrower band, a sparse copy into less storage, c A + I on a sparse matrix
// missing a diagonal entry). KLU's sparse matrix gets compiled clone, zero, copy and c A + I (a
// fifth of the chain's KLU run at N = 1e3 was in Debian's); KLU itself is SuiteSparse's build.
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

namespace contact::sundials {

// Installs the compiled operations on a dense, band or sparse matrix (its clones, CVODE's and
// ARKODE's saved Jacobian, inherit them) and on the dense or band solver that factors it (KLU keeps
// its own). Throws std::invalid_argument for another pair.
void use_compiled_matrix_ops(SUNMatrix A, SUNLinearSolver solver);

}  // namespace contact::sundials
