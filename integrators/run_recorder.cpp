#include "run_recorder.hpp"

#include <cmath>
#include <limits>

namespace contact {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

RunRecorder::RunRecorder(const MechanicalSystem& model, std::string method, double sample_dt,
                         double t_end)
    : model_(model),
      open_(model.contact_count(), -1),
      start_(std::chrono::steady_clock::now()) {
  result_.method = std::move(method);
  result_.state_labels = model.state_labels();
  result_.energy0 = model.energy(model.initial_state());
  // Grid t_j = j * sample_dt by multiplication (no accumulated round-off), closed by t_end.
  for (std::size_t j = 0; static_cast<double>(j) * sample_dt < t_end * (1 - 1e-12); ++j)
    times_.push_back(static_cast<double>(j) * sample_dt);
  times_.push_back(t_end);
}

double RunRecorder::next_sample_time() const {
  return next_sample_ < times_.size() ? times_[next_sample_]
                                      : std::numeric_limits<double>::infinity();
}

void RunRecorder::sample(double t, ConstVectorRef y) { sample(t, y, dissipated_); }

void RunRecorder::sample(double t, ConstVectorRef y, double dissipated) {
  result_.samples.push_back({t, y, model_.energy(y), dissipated});
  // Fixed-step methods sample at step ends: skip every grid time this sample stands for.
  while (next_sample_ < times_.size() && times_[next_sample_] <= t * (1 + 1e-12)) ++next_sample_;
}

void RunRecorder::contact_begin(std::size_t i, double t, double v_in) {
  open_[i] = static_cast<long>(result_.contacts.size());
  result_.contacts.push_back({i, t, kNaN, 0.0, v_in, kNaN});
}

void RunRecorder::contact_end(std::size_t i, double t, double v_out) {
  if (open_[i] < 0) return;
  auto& c = result_.contacts[static_cast<std::size_t>(open_[i])];
  c.t_end = t;
  c.v_out = v_out;
  open_[i] = -1;
}

void RunRecorder::observe_penetration(std::size_t i, double penetration) {
  if (open_[i] < 0) return;
  auto& c = result_.contacts[static_cast<std::size_t>(open_[i])];
  c.max_penetration = std::max(c.max_penetration, penetration);
}

void RunRecorder::apex(std::size_t i, double t, double gap, double energy) {
  apex(i, t, gap, energy, dissipated_);
}

void RunRecorder::apex(std::size_t i, double t, double gap, double energy, double dissipated) {
  result_.apexes.push_back({i, t, gap, energy, dissipated});
}

RunResult RunRecorder::finish(SolverStats stats, double t_reached) {
  stats.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  result_.stats = stats;
  result_.t_reached = t_reached;
  return std::move(result_);
}

RunResult RunRecorder::fail(const SolverFailure& f, SolverStats stats) {
  RunResult r = finish(stats, f.t_reached());
  r.status = f.status();
  r.message = f.solver_message();
  return r;
}

}  // namespace contact
