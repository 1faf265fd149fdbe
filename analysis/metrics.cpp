#include "contact_ode/analysis/metrics.hpp"

#include "contact_ode/analysis/fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace contact {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

RunMetrics compute_metrics(const RunResult& run) {
  RunMetrics m;
  const double scale = std::abs(run.energy0) > 0 ? std::abs(run.energy0) : 1.0;
  auto rel = [&](double E) { return (E - run.energy0) / scale; };
  for (const auto& s : run.samples)
    m.max_energy_error = std::max(m.max_energy_error, std::abs(rel(s.energy)));
  for (const auto& a : run.apexes) m.max_energy_error = std::max(m.max_energy_error, std::abs(rel(a.energy)));
  for (double d : energy_drifts(run)) m.max_energy_drift = std::max(m.max_energy_drift, std::abs(d));
  m.final_energy_error = run.samples.empty() ? kNaN : rel(run.samples.back().energy);
  m.contacts = run.contacts.size();
  m.first_penetration = m.first_duration = m.first_restitution = kNaN;
  if (!run.contacts.empty()) {
    const auto& c = run.contacts.front();
    m.first_penetration = c.max_penetration;
    if (c.closed()) {
      m.first_duration = c.duration();
      m.first_restitution = c.restitution();
    }
  }
  for (const auto& c : run.contacts) m.max_penetration = std::max(m.max_penetration, c.max_penetration);
  m.first_apex = run.apexes.empty() ? kNaN : run.apexes.front().gap;
  return m;
}

std::vector<double> energy_drifts(const RunResult& run) {
  std::vector<double> out;
  const double scale = std::abs(run.energy0) > 0 ? std::abs(run.energy0) : 1.0;
  for (const auto& s : run.samples) out.push_back((run.energy0 - s.energy - s.dissipated) / scale);
  return out;
}

std::vector<double> apex_energy_errors(const RunResult& run) {
  std::vector<double> out;
  const double scale = std::abs(run.energy0) > 0 ? std::abs(run.energy0) : 1.0;
  for (const auto& a : run.apexes) out.push_back((a.energy - run.energy0) / scale);
  return out;
}

std::string EnergyGain::verdict(double tolerance) const {
  if (!std::isfinite(rate)) return "energy not finite";
  return std::abs(final_gain) < tolerance ? "conserves" : final_gain > 0 ? "gains" : "loses";
}

EnergyGain energy_gain(const RunResult& run) {
  EnergyGain g;
  const auto drifts = energy_drifts(run);
  for (std::size_t i = 0; i < drifts.size(); ++i) {
    g.t.push_back(run.samples[i].t);
    g.gain.push_back(0.0 - drifts[i]);  // not -drifts[i]: no "-0" in the tables
  }
  if (g.gain.empty()) return g;
  g.final_gain = g.gain.back();
  // An energy beyond the doubles (k = 1e300: k x^2 / 2 overflows at any real overlap) has no
  // rate: NaN, and the verdict says so, where the fit refused it and ended the experiment.
  if (!std::all_of(g.gain.begin(), g.gain.end(), [](double v) { return std::isfinite(v); })) {
    g.rate = g.rate_sd = std::numeric_limits<double>::quiet_NaN();
    return g;
  }
  const LineFit fit = fit_line(g.t, g.gain);
  g.rate = fit.slope;
  g.rate_sd = fit.slope_sd;
  return g;
}

}  // namespace contact
