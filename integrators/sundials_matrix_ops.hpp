#pragma once
// The dense and band matrices and their LU solvers, compiled here for the reason the vectors are
// (sundials_vector_ops.hpp): Debian 12's SUNDIALS builds them without optimisation. A small
// implicit solve (P1 under CVODE BDF, a 3 x 3 Newton matrix) spent 14 % of its time (perf) in
// their copy, scale-and-add-identity, factorisation and triangular solves, the chain's band solve
// two thirds; compiled, P1 takes 9 % fewer instructions, the chain's dense solve of 1000 balls
// 4.0 s instead of 13.2 s and its band solve 67 ms instead of 79. Each operation is the library's
// algorithm with its floating-point operations in the same order (LU with partial pivoting, the
// first row of largest magnitude as the pivot, an update skipped where its multiplier is zero), so
// results are bitwise those of the library; the one case left to the library is a band copy into a narrower
// band (which reallocates the target).
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

namespace contact::sundials {

// Installs the compiled operations on a dense or band matrix (its clones, CVODE's and ARKODE's
// saved Jacobian, inherit them) and on the dense or band solver that factors it. Throws
// std::invalid_argument for another pair.
void use_compiled_matrix_ops(SUNMatrix A, SUNLinearSolver solver);

}  // namespace contact::sundials
