#include "cvode_solver.hpp"

#include "sundials_handles.hpp"

#include <cvode/cvode.h>
#include <fmt/format.h>
#include <sundials/sundials_version.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cstdlib>
#include <exception>

namespace contact {

struct CvodeSolver::Impl {
  OdeSystem sys;
  sundials::Context ctx = sundials::make_context();
  sundials::NVector y;
  sundials::Matrix A;
  sundials::LinearSolver ls;
  sundials::CvodeMemory mem;
  std::vector<int> root_directions;
  SolverStats before_reinit;   // counters of segments already closed by a re-initialisation
  std::string solver_message;  // CVODE's last error message
  std::string callback_error;  // why one of our callbacks refused
  bool non_finite = false;
  double t = 0.0;  // time of the state held in y

  Eigen::Map<Vector> map(N_Vector v) const {
    return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(sys.size)};
  }
  SolverStats segment_stats() const;
  void check(int flag, const char* call) const {
    if (flag < 0) throw SolverFailure(Status::SolverError, 0.0, fmt::format("{} failed ({})", call, flag));
  }
};

namespace {

// C callbacks: cast user_data back, call the system through Eigen maps, and turn a non-finite
// result or an exception into a refusal CVODE reports, never into a NaN that propagates.
int rhs_callback(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto& impl = *static_cast<CvodeSolver::Impl*>(user);
  auto out = impl.map(ydot);
  try {
    impl.sys.rhs(t, impl.map(y), out);
  } catch (const std::exception& e) {
    impl.callback_error = e.what();
    return -1;
  }
  if (!out.allFinite()) {
    // Recoverable: a trial state of an over-long step may leave the region where the model is
    // defined; CVODE then retries with a smaller step and fails only if the NaN persists.
    impl.non_finite = true;
    impl.callback_error = fmt::format("right-hand side is not finite at t = {:.17g}", t);
    return 1;
  }
  return 0;
}

int jacobian_callback(sunrealtype t, N_Vector y, N_Vector, SUNMatrix J, void* user, N_Vector,
                      N_Vector, N_Vector) {
  auto& impl = *static_cast<CvodeSolver::Impl*>(user);
  const auto n = static_cast<Eigen::Index>(impl.sys.size);
  Eigen::Map<Matrix> jm(SUNDenseMatrix_Data(J), n, n);  // column-major, like Eigen's default
  impl.sys.jacobian(t, impl.map(y), jm);
  return jm.allFinite() ? 0 : -1;
}

int root_callback(sunrealtype t, N_Vector y, sunrealtype* gout, void* user) {
  auto& impl = *static_cast<CvodeSolver::Impl*>(user);
  Eigen::Map<Vector> g(gout, static_cast<Eigen::Index>(impl.sys.root_count));
  impl.sys.roots(t, impl.map(y), g);
  return 0;
}

void error_handler(int code, const char* module, const char* function, char* msg, void* user) {
  if (code >= 0) return;  // warnings are not failures
  static_cast<CvodeSolver::Impl*>(user)->solver_message = fmt::format("{}:{}: {}", module, function, msg);
}

Status status_for(int flag, bool non_finite) {
  if (non_finite) return Status::NonFiniteState;  // whatever CVODE made of the refusals
  switch (flag) {
    case CV_TOO_MUCH_WORK: return Status::MaxSteps;
    case CV_CONV_FAILURE:
    case CV_LSETUP_FAIL:
    case CV_LSOLVE_FAIL: return Status::ConvergenceFailure;
    case CV_ERR_FAILURE:
    case CV_TOO_MUCH_ACC: return Status::ErrorTestFailure;
    default: return Status::SolverError;
  }
}

}  // namespace

SolverStats CvodeSolver::Impl::segment_stats() const {
  SolverStats s;
  long nfe_ls = 0, netf = 0, ncfn = 0;
  void* m = mem.get();
  CVodeGetNumSteps(m, &s.steps);
  CVodeGetNumRhsEvals(m, &s.rhs_evals);
  CVodeGetNumLinRhsEvals(m, &nfe_ls);
  CVodeGetNumErrTestFails(m, &netf);
  CVodeGetNumNonlinSolvConvFails(m, &ncfn);
  CVodeGetNumNonlinSolvIters(m, &s.newton_iters);
  CVodeGetNumJacEvals(m, &s.jac_evals);
  CVodeGetNumLinSolvSetups(m, &s.linear_setups);
  if (sys.root_count > 0) CVodeGetNumGEvals(m, &s.root_evals);
  s.rhs_evals += nfe_ls;  // difference-quotient Jacobian columns are right-hand-side calls too
  s.failed_steps = netf + ncfn;
  return s;
}

CvodeSolver::CvodeSolver(OdeSystem system, double t0, ConstVectorRef y0, const CvodeOptions& o)
    : impl_(std::make_unique<Impl>()) {
  auto& im = *impl_;
  im.sys = std::move(system);
  im.t = t0;
  const auto n = static_cast<sunindextype>(im.sys.size);
  im.y.reset(N_VNew_Serial(n, im.ctx.get()));
  im.map(im.y.get()) = y0;
  im.mem.reset(CVodeCreate(o.method == CvodeMethod::Bdf ? CV_BDF : CV_ADAMS, im.ctx.get()));
  if (!im.y || !im.mem) throw SolverFailure(Status::SolverError, t0, "CVODE allocation failed");
  void* m = im.mem.get();
  im.check(CVodeSetErrHandlerFn(m, error_handler, &im), "CVodeSetErrHandlerFn");
  im.check(CVodeInit(m, rhs_callback, t0, im.y.get()), "CVodeInit");
  im.check(CVodeSetUserData(m, &im), "CVodeSetUserData");
  im.check(CVodeSStolerances(m, o.rtol, o.atol), "CVodeSStolerances");
  im.check(CVodeSetMaxNumSteps(m, o.max_steps), "CVodeSetMaxNumSteps");
  if (o.max_step > 0) im.check(CVodeSetMaxStep(m, o.max_step), "CVodeSetMaxStep");
  im.A.reset(SUNDenseMatrix(n, n, im.ctx.get()));
  im.ls.reset(SUNLinSol_Dense(im.y.get(), im.A.get(), im.ctx.get()));
  im.check(CVodeSetLinearSolver(m, im.ls.get(), im.A.get()), "CVodeSetLinearSolver");
  if (o.jacobian == JacobianMode::Analytic && im.sys.jacobian)
    im.check(CVodeSetJacFn(m, jacobian_callback), "CVodeSetJacFn");
  if (im.sys.root_count > 0) {
    im.check(CVodeRootInit(m, static_cast<int>(im.sys.root_count), root_callback), "CVodeRootInit");
    // A ball dropped from rest starts with a zero gap rate; that is not a problem to warn about.
    im.check(CVodeSetNoInactiveRootWarn(m), "CVodeSetNoInactiveRootWarn");
  }
}

CvodeSolver::~CvodeSolver() = default;
CvodeSolver::CvodeSolver(CvodeSolver&&) noexcept = default;
CvodeSolver& CvodeSolver::operator=(CvodeSolver&&) noexcept = default;

CvodeSolver::Outcome CvodeSolver::advance(double t_out) {
  auto& im = *impl_;
  Outcome out;
  im.non_finite = false;  // only refusals during this call count towards its status
  im.callback_error.clear();
  const int flag = CVode(im.mem.get(), t_out, im.y.get(), &out.t, CV_NORMAL);
  if (flag < 0) {
    double t_reached = out.t;
    CVodeGetCurrentTime(im.mem.get(), &t_reached);
    char* name = CVodeGetReturnFlagName(flag);
    std::string msg = name ? name : "CVODE error";
    std::free(name);
    if (!im.solver_message.empty()) msg += ": " + im.solver_message;
    if (!im.callback_error.empty()) msg += " (" + im.callback_error + ")";
    throw SolverFailure(status_for(flag, im.non_finite), t_reached, msg);
  }
  im.t = out.t;
  if (flag == CV_ROOT_RETURN) {
    out.root = true;
    out.roots_found.assign(im.sys.root_count, 0);
    CVodeGetRootInfo(im.mem.get(), out.roots_found.data());
  }
  return out;
}

void CvodeSolver::reinit(double t, ConstVectorRef y) {
  auto& im = *impl_;
  im.before_reinit += im.segment_stats();  // CVodeReInit zeroes CVODE's counters
  im.before_reinit.restarts += 1;
  im.map(im.y.get()) = y;
  im.t = t;
  im.check(CVodeReInit(im.mem.get(), t, im.y.get()), "CVodeReInit");
  if (!im.root_directions.empty()) set_root_directions(im.root_directions);
}

void CvodeSolver::set_root_directions(const std::vector<int>& directions) {
  auto& im = *impl_;
  im.root_directions = directions;
  im.check(CVodeSetRootDirection(im.mem.get(), im.root_directions.data()), "CVodeSetRootDirection");
}

double CvodeSolver::t() const { return impl_->t; }

ConstVectorRef CvodeSolver::y() const { return impl_->map(impl_->y.get()); }

SolverStats CvodeSolver::stats() const {
  SolverStats s = impl_->before_reinit;
  s += impl_->segment_stats();
  return s;
}

std::string sundials_version() {
  char buf[64] = {};
  SUNDIALSGetVersion(buf, sizeof buf);
  return buf;
}

}  // namespace contact
