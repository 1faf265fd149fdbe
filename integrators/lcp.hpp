// The linear complementarity problem of contact impulses, solved exactly:
//   w = W p + b,   p >= 0,   w >= 0,   p_i w_i = 0,
// W the contacts' Delassus matrix (symmetric, positive semidefinite: J M^-1 J^T). Projected
// Gauss–Seidel, what engines use, contracts by about 1 - pi^2 / n^2 per sweep on a row of n
// touching contacts (a 1-D Laplacian), so 1e-12 of a cradle's impulse needs ~3 n^2 sweeps:
// 28000 for 100 balls. Block principal pivoting (Júdice and Pires 1994) instead guesses which p
// are positive, solves W_FF p_F = -b_F on that set, and moves every index whose p or w comes out
// negative (or, on a singular block, whose w does not vanish) to the other set; it falls back to one index at
// a time (Murty's rule, finite on a positive definite W) when the number of infeasible indices stops falling.
// Started from PGS's guess it takes a few solves. W is sparse (a contact couples only to the
// contacts that share a body with it: a column or a row of n contacts is tridiagonal), and each
// block is factorised sparse: O(n) for such a row instead of the n^3 / 3 of a dense factorisation.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <vector>

namespace contact {

struct LcpSolution {
  Eigen::VectorXd p;
  int solves = 0;  // linear solves on a principal block of W (pivot steps)
  // p_i >= -p_tol_i, w_i >= -w_floor, and |w_i| <= w_floor where p_i > 0; else p is the last iterate.
  bool solved = false;
};

// `positive`: the initial guess of the indices with p > 0. w_tol bounds the negative w allowed
// (the velocities' tolerance), raised to the rounding of w itself (w_floor: 1e-10 of the largest
// |b|); p's is w_tol / W_ii. At most max_solves pivot steps.
LcpSolution solve_lcp(const Eigen::SparseMatrix<double>& W, const Eigen::VectorXd& b,
                      std::vector<bool> positive, double w_tol, int max_solves);

}  // namespace contact
