#include "lcp.hpp"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace contact {

namespace {

// Block pivots allowed without fewer infeasible indices before single flips (Júdice and Pires).
constexpr int kBlockTrials = 3;
// What a block solve's residual may be, relative to the largest right-hand side (below).
constexpr double kResidual = 1e-10;

// p_F of W_FF p_F = -b_F. W is semidefinite, and a principal block can be singular (redundant
// contacts): a sparse LDLT first (no pivoting: it stops at a zero pivot), the minimum-norm
// least-squares solution of the dense block where LDLT's is not a solution. A backward-stable
// solve leaves a residual of about eps cond(A) of r; a row of n contacts has cond ~ 0.4 n^2 (4e5 at
// 1000), so kResidual passes every regular block and fails a singular one.
Eigen::VectorXd solve_block(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& r) {
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  const double scale = std::max(r.cwiseAbs().maxCoeff(), 1e-300);
  if (ldlt.info() == Eigen::Success) {
    Eigen::VectorXd x = ldlt.solve(r);
    if (ldlt.info() == Eigen::Success && x.allFinite() &&
        (A * x - r).cwiseAbs().maxCoeff() <= kResidual * scale)
      return x;
  }
  return Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(Eigen::MatrixXd(A)).solve(r);
}

// W's principal block on the indices `free` (ascending), from the nonzeros of their columns.
Eigen::SparseMatrix<double> principal_block(const Eigen::SparseMatrix<double>& W,
                                            const std::vector<Eigen::Index>& free,
                                            std::vector<Eigen::Index>& position) {
  const auto m = static_cast<Eigen::Index>(free.size());
  position.assign(static_cast<std::size_t>(W.rows()), -1);
  for (Eigen::Index a = 0; a < m; ++a)
    position[static_cast<std::size_t>(free[static_cast<std::size_t>(a)])] = a;
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index a = 0; a < m; ++a)
    for (Eigen::SparseMatrix<double>::InnerIterator it(W, free[static_cast<std::size_t>(a)]); it; ++it)
      if (const Eigen::Index row = position[static_cast<std::size_t>(it.row())]; row >= 0)
        entries.emplace_back(row, a, it.value());
  Eigen::SparseMatrix<double> A(m, m);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

}  // namespace

LcpSolution solve_lcp(const Eigen::SparseMatrix<double>& W, const Eigen::VectorXd& b,
                      std::vector<bool> positive, double w_tol, int max_solves) {
  const Eigen::Index n = b.size();
  if (W.rows() != n || W.cols() != n || positive.size() != static_cast<std::size_t>(n))
    throw std::invalid_argument("solve_lcp: W must be n x n and the guess of length n, n = b's length");
  LcpSolution s{.p = Eigen::VectorXd::Zero(n)};
  // w's own rounding: a solved block's w_F is zero only to its solve's residual, and a w that is
  // exactly zero comes out of W p + b with the rounding of that product. Asked of w alone, a w_tol
  // below it (1e-15 m/s on a falling 1500-ball column, the residual 2e-15) flipped a solved index
  // out and back for ever. Moreau–Jean's sweeps take the answer on to w_tol.
  const double w_floor = std::max(w_tol, kResidual * (n > 0 ? b.cwiseAbs().maxCoeff() : 0.0));
  const Eigen::VectorXd diagonal = W.diagonal();
  std::vector<Eigen::Index> free, infeasible, position;
  std::size_t fewest = static_cast<std::size_t>(n) + 1;
  int trials = kBlockTrials;
  while (s.solves < max_solves) {
    free.clear();
    for (Eigen::Index i = 0; i < n; ++i)
      if (positive[static_cast<std::size_t>(i)]) free.push_back(i);
    s.p.setZero();
    if (!free.empty()) {
      const auto m = static_cast<Eigen::Index>(free.size());
      Eigen::VectorXd r(m);
      for (Eigen::Index a = 0; a < m; ++a) r(a) = -b(free[static_cast<std::size_t>(a)]);
      const Eigen::SparseMatrix<double> A = principal_block(W, free, position);
      const Eigen::VectorXd x = solve_block(A, r);
      for (Eigen::Index a = 0; a < m; ++a) s.p(free[static_cast<std::size_t>(a)]) = x(a);
    }
    ++s.solves;
    const Eigen::VectorXd w = W * s.p + b;
    infeasible.clear();
    for (Eigen::Index i = 0; i < n; ++i) {
      // A free index whose w is not zero: its block had no solution (a singular W), only the
      // least-squares one.
      const bool out = positive[static_cast<std::size_t>(i)]
                           ? !(s.p(i) >= -w_tol / std::max(diagonal(i), 1e-300) && std::abs(w(i)) <= w_floor)
                           : !(w(i) >= -w_floor);
      if (out) infeasible.push_back(i);
    }
    if (infeasible.empty()) {
      s.p = s.p.cwiseMax(0.0);  // within the tolerance: an impulse never pulls
      s.solved = true;
      return s;
    }
    if (infeasible.size() < fewest) {
      fewest = infeasible.size();
      trials = kBlockTrials;
    } else if (trials > 0) {
      --trials;
    } else {  // Murty: flip only the largest infeasible index
      infeasible.erase(infeasible.begin(), infeasible.end() - 1);
    }
    for (const Eigen::Index i : infeasible)
      positive[static_cast<std::size_t>(i)] = !positive[static_cast<std::size_t>(i)];
  }
  return s;
}

}  // namespace contact
