#pragma once
// Runs of several methods side by side, as tables: one summary row per run (metric_cells), and
// the full record of each run (RunRecords: every contact, apex, sample and solver statistic),
// each row starting with the run's method.
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/run_result.hpp"

#include <string>
#include <vector>

namespace contact {

// status, contacts, first penetration, duration, restitution and apex, energy error and drift,
// steps, right-hand sides, Jacobians, wall time; metric_cells(r) gives them in that order.
const std::vector<std::string>& metric_columns();
std::vector<Table::Cell> metric_cells(const RunResult& r);

struct RunRecords {
  // state_columns name the sampled state components, in the model's order (e.g. y_m, v_mps).
  explicit RunRecords(const std::vector<std::string>& state_columns);
  void add(const RunResult& r);
  Table contacts, apexes, samples, stats;
};

}  // namespace contact
