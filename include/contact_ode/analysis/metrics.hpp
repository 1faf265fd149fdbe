#pragma once
// Metrics of one run. All relative energies are (E - E0) / |E0|.
#include "contact_ode/integrators/run_result.hpp"

#include <optional>
#include <string>
#include <vector>

namespace contact {

struct RunMetrics {
  double max_energy_error = 0;    // max |E - E0| / |E0| over samples and apexes
  double max_energy_drift = 0;    // max |E0 - E - dissipated| / |E0|: the numerical part
  double final_energy_error = 0;  // (E(t_end) - E0) / |E0|
  std::size_t contacts = 0;       // contacts begun
  // First contact (NaN when there is none or it never closed):
  double first_penetration = 0;  // [m]
  double first_duration = 0;     // [s]
  double first_restitution = 0;  // -v_out / v_in
  double max_penetration = 0;    // over all contacts [m]
  double first_apex = 0;         // height of the first apex after a contact [m]
};

RunMetrics compute_metrics(const RunResult& run);

// Relative energy drift (E0 - E - dissipated) / |E0| of each sample, in order.
std::vector<double> energy_drifts(const RunResult& run);
// The numerical energy error as a gain, gain(t) = (E + dissipated - E0) / |E0| = -drift, at each
// sample: its final value and its least-squares slope against time (GSL) with that slope's
// standard deviation. > 0: the method invents energy.
struct EnergyGain {
  std::vector<double> t, gain;
  double final_gain = 0, rate = 0, rate_sd = 0;  // [1], [1/s], [1/s]
  // "conserves" when |final_gain| < tolerance, else "gains" or "loses" ("energy not finite" when
  // an energy overflowed: then rate and rate_sd are NaN). The default is the
  // study's: far above the round-off of the energy over a long run, far below any method's drift.
  std::string verdict(double tolerance = 1e-10) const;
};
EnergyGain energy_gain(const RunResult& run);

// Relative energy error at each apex, in order.
std::vector<double> apex_energy_errors(const RunResult& run);

}  // namespace contact
