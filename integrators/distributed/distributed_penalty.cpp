#include "distributed_penalty.hpp"

#include "sundials_handles.hpp"

#include <cvode/cvode.h>
#include <cvode/cvode_bbdpre.h>
#include <fmt/format.h>
#include <nvector/nvector_parallel.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include <chrono>
#include <stdexcept>

namespace contact {

std::pair<std::size_t, std::size_t> block_of(std::size_t bodies, int rank, int size) {
  const auto r = static_cast<std::size_t>(rank), s = static_cast<std::size_t>(size);
  const std::size_t base = bodies / s, extra = bodies % s;
  return {r * base + std::min(r, extra), base + (r < extra ? 1 : 0)};
}

namespace {

// What the callbacks need: the block, the neighbours, and the window of the block's state with
// one body on each side (filled by exchange()).
struct Block {
  const NeighbourDynamics& parts;
  MPI_Comm comm;
  int rank, size;
  std::size_t first, count, stride;
  Vector window;
  long rhs_evals = 0;

  std::size_t left_halo() const { return first > 0 ? 1 : 0; }
  // Copies the local state into the window and swaps boundary bodies with the neighbours.
  void exchange(N_Vector y) {
    const double* local = N_VGetArrayPointer_Parallel(y);
    const auto n = static_cast<int>(stride);
    const std::size_t halo = left_halo();
    std::copy(local, local + count * stride, window.data() + halo * stride);
    const int left = rank > 0 ? rank - 1 : MPI_PROC_NULL, right = rank + 1 < size ? rank + 1 : MPI_PROC_NULL;
    // My first body to the left neighbour, its last into my right halo; then the mirror.
    MPI_Sendrecv(local, n, MPI_DOUBLE, left, 0, window.data() + (halo + count) * stride, n, MPI_DOUBLE, right,
                 0, comm, MPI_STATUS_IGNORE);
    MPI_Sendrecv(local + (count - 1) * stride, n, MPI_DOUBLE, right, 1, window.data(), n, MPI_DOUBLE, left, 1,
                 comm, MPI_STATUS_IGNORE);
  }
  void local_rhs(double t, N_Vector ydot) {
    Eigen::Map<Vector> out(N_VGetArrayPointer_Parallel(ydot), static_cast<Eigen::Index>(count * stride));
    parts.range_rhs(t, first, count, window, out);
    ++rhs_evals;
  }
};

int gloc(sunindextype, double t, N_Vector, N_Vector g, void* data) {
  static_cast<Block*>(data)->local_rhs(t, g);
  return 0;
}
int cfn(sunindextype, double, N_Vector y, void* data) {
  static_cast<Block*>(data)->exchange(y);
  return 0;
}
int rhs(double t, N_Vector y, N_Vector ydot, void* data) {
  auto* block = static_cast<Block*>(data);
  block->exchange(y);
  block->local_rhs(t, ydot);
  return 0;
}

void check(int flag, const char* call, double t) {
  if (flag < 0)
    throw SolverFailure(flag == CV_TOO_MUCH_WORK  ? Status::MaxSteps
                        : flag == CV_CONV_FAILURE ? Status::ConvergenceFailure
                                                  : Status::SolverError,
                        t, fmt::format("{}: {}", call, CVodeGetReturnFlagName(flag)));
}

}  // namespace

RunResult run_distributed(const Dynamics& scene, const NeighbourDynamics& parts,
                          const DistributedOptions& options, const SolveOptions& span, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const std::size_t n = parts.bodies(), stride = parts.body_stride();
  if (static_cast<std::size_t>(size) > n)
    throw std::invalid_argument(
        fmt::format("ranks: value '{}' exceeds the {} bodies; accepted range [1, {}]", size, n, n));
  const auto [first, count] = block_of(n, rank, size);
  Block block{parts, comm,  rank,   size,
              first, count, stride, Vector::Zero(static_cast<Eigen::Index>((count + 2) * stride))};
  const auto local = static_cast<sunindextype>(count * stride),
             global = static_cast<sunindextype>(n * stride);

  SUNContext raw_ctx = nullptr;
  if (SUNContext_Create(&comm, &raw_ctx) != 0 || raw_ctx == nullptr)
    throw std::runtime_error("SUNContext_Create failed");
  const sundials::Context ctx(raw_ctx);
  const sundials::NVector y(N_VNew_Parallel(comm, local, global, ctx.get()));
  if (!y) throw std::runtime_error("N_VNew_Parallel failed");
  const Vector y0 = scene.initial_state();
  std::copy(y0.data() + first * stride, y0.data() + (first + count) * stride,
            N_VGetArrayPointer_Parallel(y.get()));

  RunRecorder rec(scene, "penalty (distributed)", span);
  Vector whole(y0.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r) {
    const auto [f, c] = block_of(n, r, size);
    counts[static_cast<std::size_t>(r)] = static_cast<int>(c * stride);
    offsets[static_cast<std::size_t>(r)] = static_cast<int>(f * stride);
  }
  auto gather_sample = [&](double t) {
    MPI_Gatherv(N_VGetArrayPointer_Parallel(y.get()), static_cast<int>(local), MPI_DOUBLE, whole.data(),
                counts.data(), offsets.data(), MPI_DOUBLE, 0, comm);
    if (rank == 0) rec.sample(t, whole);
  };

  SolverStats stats;
  const auto start = std::chrono::steady_clock::now();
  double t = 0;
  try {
    const sundials::CvodeMemory mem(CVodeCreate(CV_BDF, ctx.get()));
    if (!mem) throw std::runtime_error("CVodeCreate failed");
    check(CVodeInit(mem.get(), rhs, 0.0, y.get()), "CVodeInit", 0.0);
    check(CVodeSetUserData(mem.get(), &block), "CVodeSetUserData", 0.0);
    check(CVodeSStolerances(mem.get(), options.integrator.rtol, options.integrator.atol), "CVodeSStolerances",
          0.0);
    check(CVodeSetMaxNumSteps(mem.get(), options.integrator.max_steps), "CVodeSetMaxNumSteps", 0.0);
    const sundials::LinearSolver ls(SUNLinSol_SPGMR(y.get(), SUN_PREC_LEFT, options.krylov_dim, ctx.get()));
    if (!ls) throw std::runtime_error("SUNLinSol_SPGMR failed");
    check(CVodeSetLinearSolver(mem.get(), ls.get(), nullptr), "CVodeSetLinearSolver", 0.0);
    // A body couples to its neighbours' two entries: half-bandwidth 2 stride - 1 in the block.
    const auto band = static_cast<sunindextype>(2 * stride - 1);
    check(CVBBDPrecInit(mem.get(), local, band, band, band, band, 0.0, gloc, cfn), "CVBBDPrecInit", 0.0);
    // Output times counted the same on every rank (only rank 0 records).
    gather_sample(0.0);
    for (long k = 1; t < span.t_end; ++k) {
      const double t_out = std::min(static_cast<double>(k) * span.sample_dt, span.t_end);
      check(CVode(mem.get(), t_out, y.get(), &t, CV_NORMAL), "CVode", t);
      gather_sample(t_out);
    }
    long steps = 0, fails = 0, jac = 0, newton = 0, lin = 0, setups = 0;
    CVodeGetNumSteps(mem.get(), &steps);
    CVodeGetNumErrTestFails(mem.get(), &fails);
    CVodeGetNumLinIters(mem.get(), &lin);
    CVodeGetNumNonlinSolvIters(mem.get(), &newton);
    CVodeGetNumLinSolvSetups(mem.get(), &setups);
    CVodeGetNumPrecEvals(mem.get(), &jac);
    stats.steps = steps;
    stats.failed_steps = fails;
    stats.linear_iters = lin;
    stats.newton_iters = newton;
    stats.linear_setups = setups;
    stats.jac_evals = jac;
    stats.rhs_evals = block.rhs_evals;
  } catch (const SolverFailure& failure) {
    return rec.fail(failure, stats);
  }
  stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return rec.finish(stats, t);
}

}  // namespace contact
