// Solver failures become typed results carrying the time reached and CVODE's message.
#include "contact_ode/integrators/event_driven.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_drop.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

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
