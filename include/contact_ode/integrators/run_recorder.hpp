#pragma once
// Builds a RunResult while a method runs: samples on a uniform output grid, the contact log
// and the apexes. Shared by the penalty, game-step and event-driven paradigms so that all three
// report the same things the same way.
#include "contact_ode/integrators/run_result.hpp"
#include "contact_ode/models/mechanical_system.hpp"
#include "contact_ode/models/memory_limit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>

namespace contact {

// Bounds on one run's work and memory, whatever the method: a run that would pass one ends with
// Status::WorkLimit and the time reached, instead of running for hours or exhausting memory.
// The defaults are far above what any experiment here needs (the study's largest run takes
// ~1e6 steps and keeps ~1e4 records) and far below what this machine can hold.
// The most records a run may be allowed (solve() refuses a larger max_records): 1e8 of them take
// some 5 GB (a contact record is 48 bytes).
inline constexpr long kMaxRecords = 100'000'000;

struct RunLimits {
  long max_steps = 100'000'000;   // integrator steps over the whole run, restarts included
  long max_records = 1'000'000;   // contact records, apexes and notifications kept
  long max_samples = 10'000'000;  // output samples (about t_end / sample_dt)
  // The run's samples and its method's working memory, estimated from above before it starts
  // (memory_estimate, solve()): a run that cannot fit is refused instead of filling the machine.
  double max_memory_bytes = half_the_memory_limit();
  // A sampled state entry past this many times the initial state's largest (or 1, the state being
  // in SI units) ends the run as Status::Diverged: a fixed step beyond its scheme's stability bound
  // (the default chain under semi-implicit Euler at 1 ms reached 1e43 m/s) otherwise 'succeeded'
  // with the exploded state. MuJoCo's mjMAXVAL draws the same line at 1e10. Explicit Euler's
  // energy growth that the study measures stays far below it (2650 E0: 50 times the speeds).
  double max_state_growth = 1e10;
  // A sampled energy (the ledger's E + D, which a passive scene's exact motion keeps at E0) more
  // than this many times |E0| (or 1 J) above E0 also ends the run as Status::Diverged. Energy is
  // quadratic in the speeds, so this is a 1e3-fold gain in the state's energy norm: an unstable
  // run that saturates (MuJoCo's soft springs on a 16-ball column at 1 ms: 5e8 E0, its top ball
  // 238 m up) or grows slowly never reaches the state line above and 'succeeded'. The gains the
  // study measures over its spans stay below it: projection's 392 E0 on a resting ball over 2 s
  // (unbounded in time: the ball it holds keeps its speed g t), explicit Euler's 5e4 E0 over the
  // ball drop's coarsest steps.
  double max_energy_gain = 1e6;
};

// What every run shares, whichever method: the time span, the output grid and the work bounds.
// The one place they live; a method's own options hold only its own settings.
struct SolveOptions {
  double t_end = 3.0;       // the run covers [0, t_end] [s]
  double sample_dt = 0.01;  // output spacing [s] (fixed-step methods: rounded to whole steps)
  RunLimits limits;
  // Called with the time of each sample as it is recorded: a front end's display of how far a
  // long run has come (an experiment's line on a terminal). It must not throw; empty: not called.
  std::function<void(double t)> progress;
};

// Fixed steps of dt that cover [0, t_end], the last one shortened to land on t_end: at least one
// (a span below 1e-9 dt was none, and the run 'succeeded' at t = 0), and a span within 1e-9 dt of
// a whole number of steps takes that many. Counted in floating point: t_end / dt can exceed every
// integer type (1e4 s at 1e-16 s).
inline double steps_to_cover(double t_end, double dt) { return std::max(1.0, std::ceil(t_end / dt - 1e-9)); }

// Why `steps` fixed steps of `passes` sub-steps or solver sweeps each exceed `limits`' work bound,
// if they do (the run then fails at once, as Status::WorkLimit, instead of running for days).
std::optional<std::string> fixed_step_work_refusal(double steps, int passes, const RunLimits& limits);

class RunRecorder {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

 public:
  RunRecorder(const Dynamics& model, std::string method, const SolveOptions& span);

  // Measures, from E0 on, the model's energy without the elastic energy of its penalty springs at
  // an overlap (Dynamics::energy_without_springs): for the methods that resolve contact by
  // impulses or constraints, which have no springs and must not count theirs.
  void exclude_spring_energy();
  double energy(ConstVectorRef y) const {
    return springless_ ? model_.energy_without_springs(y) : model_.energy(y);
  }

  // The next output time still to be recorded (t_end included); +inf when all are done. The grid is
  // t_j = j * sample_dt by multiplication (no accumulated round-off), closed by t_end; -1 marks it
  // as done.
  double next_sample_time() const {
    if (next_sample_ < 0) return std::numeric_limits<double>::infinity();
    const double t = static_cast<double>(next_sample_) * sample_dt_;
    return t < t_end_ * (1 - 1e-12) ? t : t_end_;
  }
  // Records the state at t and moves past every output time up to t, with the dissipated energy
  // booked so far (or `dissipated`, when the method integrates it itself).
  void sample(double t, ConstVectorRef y);
  void sample(double t, ConstVectorRef y, double dissipated);
  // Books energy a physical loss removed (an impulse with e < 1).
  void add_dissipated(double energy) { dissipated_ += energy; }

  bool contact_open(std::size_t i) const { return open_[i] >= 0; }
  void contact_begin(std::size_t i, double t, double v_in) {
    check_records(t);
    open_[i] = last_[i] = static_cast<long>(result_.contacts.size());
    result_.contacts.push_back({i, t, kNaN, 0.0, v_in, kNaN});
  }
  // The gap rate contact i's open record began with; NaN when none is open.
  double open_v_in(std::size_t i) const {
    return open_[i] < 0 ? kNaN : result_.contacts[static_cast<std::size_t>(open_[i])].v_in;
  }
  void contact_end(std::size_t i, double t, double v_out) {
    if (open_[i] < 0) return;
    auto& c = result_.contacts[static_cast<std::size_t>(open_[i])];
    c.t_end = t;
    c.v_out = v_out;
    open_[i] = -1;
  }
  // Reopens contact i's last record if it ended at or after t (a contact that goes on); returns
  // whether it did.
  bool reopen_contact(std::size_t i, double t);
  void observe_penetration(std::size_t i, double penetration) {
    if (open_[i] < 0) return;
    auto& c = result_.contacts[static_cast<std::size_t>(open_[i])];
    c.max_penetration = std::max(c.max_penetration, penetration);
  }
  void notify(const std::vector<CollisionEvent>& batch) {
    if (!batch.empty()) check_records(batch.front().t);
    result_.notifications.insert(result_.notifications.end(), batch.begin(), batch.end());
  }
  // Records the top of a bounce of contact i: only after the contact's first record, so that apex
  // n follows impact n. A ball thrown up rises to a top before its first impact; counted, it was
  // every method's 'first apex' (ball_drop --v0 2: 1.204 m for the rigid 0.770 m).
  void apex(std::size_t i, double t, double gap, double energy) { apex(i, t, gap, energy, dissipated_); }
  void apex(std::size_t i, double t, double gap, double energy, double dissipated) {
    if (last_[i] < 0) return;
    check_records(t);
    result_.apexes.push_back({i, t, gap, energy, dissipated});
  }

  // Throws SolverFailure(WorkLimit) at t when `steps` passes the run's step limit.
  void check_steps(long steps, double t) const;

  // Closes the result; open contacts stay with t_end = v_out = NaN.
  RunResult finish(SolverStats stats, double t_reached);
  RunResult fail(const SolverFailure& f, SolverStats stats);

 private:
  // Throws SolverFailure(WorkLimit) at t when the records kept reach the run's limit. Inline, as
  // the recording functions above: the closed-form event loop records an impact in ~100 ns.
  void check_records(double t) const {
    const auto kept = result_.contacts.size() + result_.apexes.size() + result_.notifications.size();
    if (static_cast<long>(kept) >= limits_.max_records) [[unlikely]]
      records_exceeded(t);
  }
  [[noreturn]] void records_exceeded(double t) const;
  void check_diverged(double t, ConstVectorRef y, double gain) const;

  const Dynamics& model_;
  bool springless_ = false;  // exclude_spring_energy()
  RunResult result_;
  RunLimits limits_;
  double sample_dt_, t_end_;  // output grid t_j = j sample_dt, closed by t_end (computed, not stored)
  std::function<void(double)> progress_;
  double dissipated_ = 0.0;
  double state_scale_ = 1.0;  // the initial state's largest entry, at least 1
  long next_sample_ = 0;
  std::vector<long> open_;  // index into result_.contacts of the open contact, or -1
  std::vector<long> last_;  // index of contact i's last record, or -1
  std::chrono::steady_clock::time_point start_;
};

}  // namespace contact
