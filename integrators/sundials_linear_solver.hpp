#pragma once
// The matrix and linear solver an implicit SUNDIALS integrator (CVODE, ARKODE) uses, built from
// the options, and the copy of a sparse Jacobian into that matrix.
//   dense   SUNDenseMatrix + SUNLinSol_Dense
//   band    SUNBandMatrix (the Jacobian's band) + SUNLinSol_Band
//   klu     SUNSparseMatrix (CSC) + SUNLinSol_KLU (SuiteSparse)
//   gmres   matrix-free SUNLinSol_SPGMR; J v from the analytic Jacobian or difference quotients;
//           optionally left-preconditioned by SUNDIALS' banded difference-quotient preconditioner
// Dense, band and KLU's sparse matrix run with the project's compiled operations (sundials_matrix_ops.hpp);
// KLU keeps its symbolic analysis across re-initialisations while the pattern stays (the .cpp says why).
#include "contact_ode/integrators/integrator.hpp"
#include "sundials_handles.hpp"

namespace contact::sundials {

struct LinearSystem {
  Matrix matrix;  // empty for matrix-free GMRES
  LinearSolver solver;
};

// `kind` is a concrete one (the caller resolves Auto: has_narrow_band).
LinearSystem make_linear_system(LinearSolverKind kind, N_Vector y_template, Bandwidth band, long nonzeros,
                                SUNContext ctx);

// Copies J into A (dense, band or CSC sparse); false if J does not fit A's pattern or band.
bool copy_jacobian(const SparseMatrix& J, SUNMatrix A);

// J v with J computed by the last jtsetup; shared by CVODE's and ARKODE's jtimes callbacks.
void multiply(const SparseMatrix& J, N_Vector v, N_Vector Jv);

}  // namespace contact::sundials
