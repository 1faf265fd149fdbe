// Solver failures become typed results carrying the time reached and CVODE's message.
#include "contact_ode/integrators/event_driven.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_drop.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <mutex>
#include <thread>

using namespace contact;

TEST(SolverFailure, TooFewStepsStopsWithMaxStepsTheTimeReachedAndCvodesMessage) {
  const BallDrop model({1.0, 9.81, 1.0, 0.0, 0.8, Hooke{1e8}});
  PenaltyOptions o;
  SolveOptions o_span;
  o_span.t_end = 1.0;
  o_span.sample_dt = 1.0;  // one output interval: the step budget applies to all of it
  o.integrator.max_steps = 20;
  const RunResult r = run_penalty(model, o, o_span);
  EXPECT_EQ(r.status, Status::MaxSteps);
  EXPECT_GT(r.t_reached, 0.0);
  EXPECT_LT(r.t_reached, 1.0);
  EXPECT_NE(r.message.find("CV_TOO_MUCH_WORK"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("mxstep"), std::string::npos) << r.message;  // CVODE's own words
}

// A model whose force turns NaN below a depth, standing in for any non-finite right-hand side.
class PoisonedBall final : public MechanicalSystem {
 public:
  explicit PoisonedBall(BallDropParams p) : ball_(p) {}
  std::string name() const override { return "poisoned"; }
  Mask position_mask() const override { return ball_.position_mask(); }
  std::size_t state_size() const override { return 2; }
  Vector initial_state() const override { return ball_.initial_state(); }
  std::vector<std::string> state_labels() const override { return ball_.state_labels(); }
  void rhs(double t, ConstVectorRef y, const ContactModes& m, VectorRef yd) const override {
    ball_.rhs(t, y, m, yd);
    if (y[0] < -1e-4) yd[1] = std::numeric_limits<double>::quiet_NaN();
  }
  void jacobian(double t, ConstVectorRef y, const ContactModes& m, SparseMatrix& J) const override {
    ball_.jacobian(t, y, m, J);
  }
  double energy(ConstVectorRef y) const override { return ball_.energy(y); }
  double energy_without_springs(ConstVectorRef y) const override { return ball_.energy_without_springs(y); }
  double mean_mass() const override { return ball_.mean_mass(); }
  std::size_t contact_count() const override { return 1; }
  double gap(std::size_t i, ConstVectorRef y) const override { return ball_.gap(i, y); }
  double gap_rate(std::size_t i, ConstVectorRef y) const override { return ball_.gap_rate(i, y); }
  double switching(std::size_t i, ConstVectorRef y) const override { return ball_.switching(i, y); }
  double dissipated_power(std::size_t i, ConstVectorRef y) const override {
    return ball_.dissipated_power(i, y);
  }
  double elastic_energy(std::size_t i, ConstVectorRef y) const override { return ball_.elastic_energy(i, y); }
  double restitution(std::size_t i) const override { return ball_.restitution(i); }
  void project(std::size_t i, VectorRef y) const override { ball_.project(i, y); }
  double apply_impulse(std::size_t i, double e, VectorRef y) const override {
    return ball_.apply_impulse(i, e, y);
  }
  void settle(std::size_t i, VectorRef y) const override { ball_.settle(i, y); }

 private:
  BallDrop ball_;
};

TEST(SolverFailure, NonFiniteRightHandSideIsReportedNotPropagated) {
  const PoisonedBall model({1.0, 9.81, 1.0, 0.0, 0.8, Hooke{1e5}});
  PenaltyOptions o;
  SolveOptions o_span;
  o_span.t_end = 1.0;
  const RunResult r = run_penalty(model, o, o_span);
  EXPECT_EQ(r.status, Status::NonFiniteState) << r.message;
  // Trial states of over-long steps may touch the poison earlier; those are retried with smaller
  // steps. The run fails only where the trajectory itself gets there: 1e-4 m below the floor,
  // i.e. within the first contact, just after the impact at t0 = sqrt(2 h0 / g) = 0.4515 s.
  EXPECT_NEAR(r.t_reached, std::sqrt(2 / 9.81), 1e-3);
  EXPECT_NE(r.message.find("not finite"), std::string::npos) << r.message;
  for (const auto& s : r.samples) EXPECT_TRUE(s.y.allFinite());
}

// Turns a run that never returns into a failed test: after `seconds` it requests the stop a
// program's Ctrl-C would, which ends a solve that still calls the model (Status::Interrupted).
// The runs below end within milliseconds; the guard is there for the code they were written
// against, which looped inside SUNDIALS.
class HangGuard {
 public:
  explicit HangGuard(double seconds)
      : thread_([this, seconds] {
          std::unique_lock lock(mutex_);
          if (!done_cv_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return done_; }))
            request_stop();
        }) {}
  ~HangGuard() {
    {
      std::lock_guard lock(mutex_);
      done_ = true;
    }
    done_cv_.notify_one();
    thread_.join();
    clear_stop_request();
  }

 private:
  std::mutex mutex_;
  std::condition_variable done_cv_;
  bool done_ = false;
  std::thread thread_;
};

// A ball at rest on the floor over 5e307 s, the first output 2.5e305 s away: CVODE's first-step
// estimate overflows to inf, and it called the right-hand side at t = inf over and over, never
// returning. A time that is not finite now ends the run at once, naming the overflow.
TEST(SolverFailure, ATimeSpanThatOverflowsTheSolversTimeEndsTheRunNamingIt) {
  const BallDrop model({1.0, 9.81, 0.0, 0.0, 0.8, Hooke{1e5}});
  EventOptions o;
  const SolveOptions span{.t_end = 5e307, .sample_dt = 2.5e305};
  RunResult r;
  {
    const HangGuard guard(20.0);
    r = run_event_driven(model, o, span);
  }
  EXPECT_EQ(r.status, Status::NonFiniteState) << r.message;
  EXPECT_EQ(r.t_reached, 0.0);
  EXPECT_NE(r.message.find("time overflowed"), std::string::npos) << r.message;
}

// A ball dropped from 1 m over 1e300 s: ARKODE's explicit first step (some 1e135 s) overflows, and
// its root search, handed root functions of -inf and NaN, looped forever (calling no right-hand
// side, so not even a stop request ended it). The root functions are now guarded as a right-hand
// side is: their time and values not finite end the run.
TEST(SolverFailure, NonFiniteRootFunctionsEndTheRunInsteadOfTheRootSearchLoopingForever) {
  const BallDrop model({1.0, 9.81, 1.0, 0.0, 0.8, Hooke{1e5}});
  EventOptions o;
  o.integrator.method = "arkode-erk";
  const SolveOptions span{.t_end = 1e300, .sample_dt = 1e298};
  RunResult r;
  {
    const HangGuard guard(20.0);
    r = run_event_driven(model, o, span);
  }
  EXPECT_EQ(r.status, Status::NonFiniteState) << r.message;
  EXPECT_NE(r.message.find("ARK_RTFUNC_FAIL"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("root functions"), std::string::npos) << r.message;
}
