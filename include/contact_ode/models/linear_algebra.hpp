#pragma once
// The vector and matrix types shared by models and integrators (Eigen, dynamic size).
#include <Eigen/Dense>
#include <Eigen/SparseCore>

namespace contact {
using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;
// A read-only view, passed by const reference as Eigen advises: by value, every layer a state
// passes through (an integrator's callback, the energy ledger's wrapper, the mechanical system's,
// the model) copied it, and each copy's destructor freed its unused plain-object member (a call to
// free(nullptr)). P1 under GSL's RK8PD: 6.5 % fewer instructions and 16 % less time by reference.
// Return a view by value (Eigen::Ref<const Vector>): a reference would dangle.
using ConstVectorRef = const Eigen::Ref<const Vector>&;
// The same view held by value, built once where one state is read by many calls: handed a Vector
// or a VectorRef, each call builds (and destroys) a temporary view of its own. The view follows
// the state's values, and stays valid while the state keeps its storage (is not resized).
using ConstVectorView = Eigen::Ref<const Vector>;
using VectorRef = Eigen::Ref<Vector>;
using MatrixRef = Eigen::Ref<Matrix>;
// Jacobians: compressed column storage, the layout of SUNDIALS' sparse (KLU) matrices.
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor>;
using Triplet = Eigen::Triplet<double>;
// Which state entries are positions (true) rather than velocities.
using Mask = Eigen::Array<bool, Eigen::Dynamic, 1>;

// Non-zero band of a Jacobian: entry (i, j) may be non-zero only if -lower <= j - i <= upper.
struct Bandwidth {
  long lower = 0;
  long upper = 0;
  // Whether band storage of a matrix of `size` rows pays: the band is narrower than the matrix
  // (bench_chain, both LUs compiled alike: level with dense at 10 balls, 3.5 to 4x faster at 100,
  // 70 to 80x at 1000 in the benchmark runs of 2026-11-28).
  bool narrower_than(long size) const { return lower + upper + 1 < size; }
};
}  // namespace contact
