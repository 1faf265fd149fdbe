#pragma once
// Builds a RunResult while a method runs: samples on a uniform output grid, the contact log
// and the apexes. Shared by the penalty, game-step and event-driven paradigms so that all three
// report the same things the same way.
#include "mechanical_system.hpp"
#include "run_result.hpp"

#include <chrono>

namespace contact {

class RunRecorder {
 public:
  RunRecorder(const MechanicalSystem& model, std::string method, double sample_dt, double t_end);

  // The next output time still to be recorded (t_end included); +inf when all are done.
  double next_sample_time() const;
  // Records the state at t and moves past every output time up to t, with the dissipated energy
  // booked so far (or `dissipated`, when the method integrates it itself).
  void sample(double t, ConstVectorRef y);
  void sample(double t, ConstVectorRef y, double dissipated);
  // Books energy a physical loss removed (an impulse with e < 1).
  void add_dissipated(double energy) { dissipated_ += energy; }

  bool contact_open(std::size_t i) const { return open_[i] >= 0; }
  void contact_begin(std::size_t i, double t, double v_in);
  void contact_end(std::size_t i, double t, double v_out);
  void observe_penetration(std::size_t i, double penetration);
  void notify(const std::vector<CollisionEvent>& batch) {
    result_.notifications.insert(result_.notifications.end(), batch.begin(), batch.end());
  }
  void apex(std::size_t i, double t, double gap, double energy);
  void apex(std::size_t i, double t, double gap, double energy, double dissipated);

  // Closes the result; open contacts stay with t_end = v_out = NaN.
  RunResult finish(SolverStats stats, double t_reached);
  RunResult fail(const SolverFailure& f, SolverStats stats);

 private:
  const MechanicalSystem& model_;
  RunResult result_;
  std::vector<double> times_;  // output grid
  double dissipated_ = 0.0;
  std::size_t next_sample_ = 0;
  std::vector<long> open_;  // index into result_.contacts of the open contact, or -1
  std::chrono::steady_clock::time_point start_;
};

}  // namespace contact
