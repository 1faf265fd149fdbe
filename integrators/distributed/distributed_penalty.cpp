#include "distributed_penalty.hpp"

#include "sundials_handles.hpp"

#include <cvode/cvode.h>
#include <cvode/cvode_bbdpre.h>
#include <fmt/format.h>
#include <nvector/nvector_parallel.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include <chrono>
#include <optional>
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

// CVODE's message for its failures, kept instead of printed (its warnings are not failures).
void keep_message(int code, const char* module, const char* function, char* msg, void* user) {
  if (code < 0) *static_cast<std::string*>(user) = fmt::format("{}:{}: {}", module, function, msg);
}

void check(int flag, const char* call, double t, const std::string& message = {}) {
  if (flag < 0)
    throw SolverFailure(flag == CV_TOO_MUCH_WORK  ? Status::MaxSteps
                        : flag == CV_CONV_FAILURE ? Status::ConvergenceFailure
                                                  : Status::SolverError,
                        t,
                        fmt::format("{}: {}{}", call, CVodeGetReturnFlagName(flag),
                                    message.empty() ? "" : " (" + message + ")"));
}

// Steps between two checkpoints: the ranks agree on a stop request this often.
constexpr long kCheckpointSteps = 16;

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
  // Rank 0's recorder may refuse a sample (the sample bound, a diverged state): its verdict goes to
  // every rank, which would otherwise go on into the integrator's next reduction and wait there
  // for rank 0 for ever.
  auto gather_sample = [&](N_Vector state, double t) {
    MPI_Gatherv(N_VGetArrayPointer_Parallel(state), static_cast<int>(local), MPI_DOUBLE, whole.data(),
                counts.data(), offsets.data(), MPI_DOUBLE, 0, comm);
    std::optional<SolverFailure> refused;
    if (rank == 0) {
      try {
        rec.sample(t, whole);
      } catch (const SolverFailure& f) {
        refused = f;
      }
    }
    int verdict = refused ? static_cast<int>(refused->status()) : -1;
    MPI_Bcast(&verdict, 1, MPI_INT, 0, comm);
    if (refused) throw *refused;
    if (verdict >= 0)
      throw SolverFailure(static_cast<Status>(verdict), t,
                          "rank 0's recorder refused the sample (its message there)");
  };

  SolverStats stats;
  const auto start = std::chrono::steady_clock::now();
  double t = 0;
  std::string message;
  try {
    const sundials::CvodeMemory mem(CVodeCreate(CV_BDF, ctx.get()));
    if (!mem) throw std::runtime_error("CVodeCreate failed");
    const sundials::NVector out(N_VClone(y.get()));
    if (!out) throw std::runtime_error("N_VClone failed");
    check(CVodeSetErrHandlerFn(mem.get(), keep_message, &message), "CVodeSetErrHandlerFn", 0.0);
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
    check(CVodeSetStopTime(mem.get(), span.t_end), "CVodeSetStopTime", 0.0);
    // Output times counted the same on every rank (only rank 0 records).
    gather_sample(y.get(), 0.0);
    // One internal step at a time, so that between steps the run can check that t advanced (a
    // step below the rounding of t leaves it where it was, and CVODE would go on so for max_steps
    // steps: the chain at k = 1e-300 did, for hours) and let every rank look in at a checkpoint.
    long k = 1, taken = 0;
    double t_out = std::min(span.sample_dt, span.t_end);
    bool recorded_end = false;
    while (t < span.t_end) {
      const double before = t;
      const int flag = CVode(mem.get(), span.t_end, y.get(), &t, CV_ONE_STEP);  // t: the time reached
      check(flag, "CVode", t, message);
      if (!(t > before))
        throw SolverFailure(
            Status::NoProgress, t,
            fmt::format("CVODE's step no longer advances t = {:g} s (below its rounding)", t));
      if (++taken > options.integrator.max_steps)
        throw SolverFailure(
            Status::MaxSteps, t,
            fmt::format("{} steps: more than the {} allowed", taken, options.integrator.max_steps));
      for (; t_out <= t && !recorded_end;
           t_out = std::min(static_cast<double>(++k) * span.sample_dt, span.t_end)) {
        check(CVodeGetDky(mem.get(), t_out, 0, out.get()), "CVodeGetDky", t, message);
        gather_sample(out.get(), t_out);
        recorded_end = t_out >= span.t_end;
      }
      if (taken % kCheckpointSteps == 0) {
        int stop = stop_requested() ? 1 : 0;
        MPI_Allreduce(MPI_IN_PLACE, &stop, 1, MPI_INT, MPI_MAX, comm);
        if (stop != 0) throw SolverFailure(Status::Interrupted, t, "a stop was requested on a rank");
        if (options.progress) options.progress(t);
      }
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
