#pragma once
// Move-only owners for every SUNDIALS object the project creates. Each handle frees its object
// with the matching SUNDIALS destructor; nothing outside integrators/ sees a raw handle.
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <memory>
#include <type_traits>

namespace contact::sundials {

struct ContextFree {
  void operator()(SUNContext ctx) const { SUNContext_Free(&ctx); }
};
struct VectorFree {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixFree {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct LinearSolverFree {
  void operator()(SUNLinearSolver ls) const { SUNLinSolFree(ls); }
};
struct CvodeFree {
  void operator()(void* mem) const { CVodeFree(&mem); }
};

struct ArkStepFree {
  void operator()(void* mem) const { ARKStepFree(&mem); }
};
struct ErkStepFree {
  void operator()(void* mem) const { ERKStepFree(&mem); }
};

using Context = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextFree>;
using NVector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorFree>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixFree>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverFree>;
using CvodeMemory = std::unique_ptr<void, CvodeFree>;
using ArkStepMemory = std::unique_ptr<void, ArkStepFree>;
using ErkStepMemory = std::unique_ptr<void, ErkStepFree>;

Context make_context();

}  // namespace contact::sundials
