#include "contact_ode/integrators/run_recorder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

namespace contact {

RunRecorder::RunRecorder(const Dynamics& model, std::string method, const SolveOptions& span)
    : model_(model),
      limits_(span.limits),
      sample_dt_(span.sample_dt),
      t_end_(span.t_end),
      progress_(span.progress),
      open_(model.contact_count(), -1),
      last_(model.contact_count(), -1),
      start_(std::chrono::steady_clock::now()) {
  result_.method = std::move(method);
  result_.state_labels = model.state_labels();
  const Vector y0 = model.initial_state();
  result_.energy0 = model.energy(y0);
  if (y0.size() > 0 && y0.allFinite()) state_scale_ = std::max(1.0, y0.cwiseAbs().maxCoeff());
}

void RunRecorder::sample(double t, ConstVectorRef y) { sample(t, y, dissipated_); }

void RunRecorder::sample(double t, ConstVectorRef y, double dissipated) {
  // The grid's size is checked before the first sample, so the index below cannot overflow.
  const double grid = t_end_ / sample_dt_;
  if (!(grid < static_cast<double>(limits_.max_samples)) ||
      static_cast<long>(result_.samples.size()) >= limits_.max_samples)
    throw SolverFailure(
        Status::WorkLimit, t,
        fmt::format("t_end / sample_dt = {:.3g} output samples; at most {} are kept: raise the "
                    "sample spacing",
                    grid, limits_.max_samples));
  const double e = energy(y);
  result_.samples.push_back({t, y, e, dissipated});
  check_diverged(t, y, e + dissipated - result_.energy0);  // after the push: the last sample shows it
  if (progress_) progress_(t);
  // Fixed-step methods sample at step ends: skip every grid time this sample stands for, in one
  // jump (a step may stand for many grid times).
  if (next_sample_ < 0) return;
  if (t >= t_end_ * (1 - 1e-12)) {
    next_sample_ = -1;
    return;
  }
  const double j = std::floor(t * (1 + 1e-12) / sample_dt_);
  next_sample_ = std::max(next_sample_, static_cast<long>(j) + 1);
}

void RunRecorder::records_exceeded(double t) const {
  throw SolverFailure(
      Status::WorkLimit, t,
      fmt::format("more than {} contact records, apexes and notifications: the run's record limit",
                  limits_.max_records));
}

void RunRecorder::check_diverged(double t, ConstVectorRef y, double gain) const {
  if (y.size() == 0 || !y.allFinite()) return;  // a non-finite state is the methods' own failure
  Eigen::Index at = 0;
  const double largest = y.cwiseAbs().maxCoeff(&at);
  const double energy_scale = std::abs(result_.energy0) > 0 ? std::abs(result_.energy0) : 1.0;
  const bool state_past = largest > limits_.max_state_growth * state_scale_;
  const bool energy_past = gain > limits_.max_energy_gain * energy_scale;
  if (!state_past && !energy_past) return;
  constexpr std::string_view unstable =
      "the method is unstable at these settings (a fixed step beyond its stability bound: "
      "contact_advisor gives a stable one; or a tolerance that lets the error grow)";
  std::string what;
  if (energy_past) {  // a passive scene's ledger can only fall: the method made the energy
    what = fmt::format(
        "the energy (with what the run booked as lost) rose {:.3g} J above its initial {:.3g} J, "
        "more than {:g} times |E0| (or 1 J): {}",
        gain, result_.energy0, limits_.max_energy_gain, unstable);
  } else {
    // The state left its initial scale while the ledger stayed within its line: that may be the
    // motion itself (a weight far beyond what the contact holds sinks through it, its sag m g / k
    // past the line, the energy conserved) as much as an unstable method.
    // A state past 1e154 squares past the doubles: its energy read "-nan J" (inf - inf).
    const auto i = static_cast<std::size_t>(at);
    const std::string energy =
        std::isfinite(gain) ? fmt::format("{:.3g} J from its initial {:.3g} J", gain, result_.energy0)
                            : fmt::format("past the doubles' range (its initial {:.3g} J)", result_.energy0);
    what = fmt::format(
        "{} = {:.3g} is more than {:g} times the initial state's largest entry (or 1), the energy "
        "(with what the run booked as lost) {}: either the motion itself leaves that scale (a load "
        "the contact cannot hold, such as a weight m g whose sag m g / k is beyond it) or {}",
        i < result_.state_labels.size() ? result_.state_labels[i] : fmt::format("y[{}]", i), y[at],
        limits_.max_state_growth, energy, unstable);
  }
  throw SolverFailure(Status::Diverged, t, what);
}

std::optional<std::string> fixed_step_work_refusal(double steps, int passes, const RunLimits& limits) {
  if (steps * passes <= static_cast<double>(limits.max_steps)) return std::nullopt;
  // "7.1e7 steps of 10 sub-steps each: more than the 1e8" read as a wrong comparison: the total is said.
  return fmt::format(
      "{:g} steps{}: more than the {} steps a run may take", steps,
      passes > 1 ? fmt::format(" of {} sub-steps or sweeps each, {:g} in all", passes, steps * passes) : "",
      limits.max_steps);
}

void RunRecorder::check_steps(long steps, double t) const {
  if (steps <= limits_.max_steps) return;
  // The contacts say where the steps went: a law whose restitution tends to 1 as impacts slow
  // (Hunt-Crossley's) bounces ever more often, without end (1e6 contacts by 1.3 s of a stiff
  // drop under it), which reads as a run that hangs until the limit is reached.
  const auto& c = result_.contacts;
  throw SolverFailure(
      Status::WorkLimit, t,
      fmt::format("more than {} steps in the run{}", limits_.max_steps,
                  c.empty() ? ""
                            : fmt::format(" (contacts recorded by then: {}, the last begun at t = {:.6g} s)",
                                          c.size(), c.back().t_begin)));
}

bool RunRecorder::reopen_contact(std::size_t i, double t) {
  if (open_[i] >= 0 || last_[i] < 0) return false;
  auto& c = result_.contacts[static_cast<std::size_t>(last_[i])];
  if (!(c.t_end >= t)) return false;
  c.t_end = c.v_out = kNaN;
  open_[i] = last_[i];
  return true;
}

void RunRecorder::exclude_spring_energy() {
  springless_ = true;
  result_.energy0 = energy(model_.initial_state());
}

RunResult RunRecorder::finish(SolverStats stats, double t_reached) {
  // The fixed-step loops look at a step's contacts in index order, each begun (or at its top) at
  // its own time within the step: two that begin in one step were logged out of time order (a
  // four-ball column under the symplectic spring, 5 of 316 records), and the 'first contact' of
  // a table was the lower index. A contact's own records never overlap, so a stable sort by time
  // keeps each contact's sequence and the event methods' order at one instant.
  const auto by_begin = [](const ContactRecord& a, const ContactRecord& b) { return a.t_begin < b.t_begin; };
  const auto by_time = [](const Apex& a, const Apex& b) { return a.t < b.t; };
  auto& c = result_.contacts;
  if (!std::is_sorted(c.begin(), c.end(), by_begin)) std::stable_sort(c.begin(), c.end(), by_begin);
  auto& a = result_.apexes;
  if (!std::is_sorted(a.begin(), a.end(), by_time)) std::stable_sort(a.begin(), a.end(), by_time);
  stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
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
