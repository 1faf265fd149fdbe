#include "contact_ode/analysis/run_tables.hpp"

#include "contact_ode/analysis/metrics.hpp"

namespace contact {

const std::vector<std::string>& metric_columns() {
  static const std::vector<std::string> columns = {"status",
                                                   "contacts",
                                                   "first_penetration_m",
                                                   "first_duration_s",
                                                   "first_restitution",
                                                   "first_apex_m",
                                                   "max_energy_change_rel",
                                                   "energy_drift_rel",
                                                   "steps",
                                                   "rhs_evals",
                                                   "jac_evals",
                                                   "wall_time_s"};
  return columns;
}

std::vector<Table::Cell> metric_cells(const RunResult& r) {
  const RunMetrics m = compute_metrics(r);
  return {std::string(to_string(r.status)),
          static_cast<long>(m.contacts),
          m.first_penetration,
          m.first_duration,
          m.first_restitution,
          m.first_apex,
          m.max_energy_error,
          m.max_energy_drift,
          r.stats.steps,
          r.stats.rhs_evals,
          r.stats.jac_evals,
          r.stats.wall_time_s};
}

namespace {
std::vector<std::string> sample_columns(const std::vector<std::string>& state) {
  std::vector<std::string> c{"method", "t_s"};
  c.insert(c.end(), state.begin(), state.end());
  c.insert(c.end(), {"energy_J", "dissipated_J"});
  return c;
}
}  // namespace

RunRecords::RunRecords(const std::vector<std::string>& state_columns)
    : contacts({"method", "t_begin_s", "t_end_s", "max_penetration_m", "v_in_mps", "v_out_mps"}),
      apexes({"method", "t_s", "height_m", "energy_J", "energy_change_rel"}),
      samples(sample_columns(state_columns)),
      stats({"method", "status", "t_reached_s", "steps", "failed_steps", "rhs_evals", "jac_evals",
             "newton_iters", "linear_setups", "root_evals", "events", "restarts", "wall_time_s",
             "setup_cpu_s", "message"}) {}

void RunRecords::add(const RunResult& r) {
  for (const auto& c : r.contacts)
    contacts.add_row({r.method, c.t_begin, c.t_end, c.max_penetration, c.v_in, c.v_out});
  const auto drift = apex_energy_errors(r);
  for (std::size_t j = 0; j < r.apexes.size(); ++j)
    apexes.add_row({r.method, r.apexes[j].t, r.apexes[j].gap, r.apexes[j].energy, drift[j]});
  const std::size_t n = samples.columns().size() - 4;  // the state components kept
  for (const auto& s : r.samples) {
    std::vector<Table::Cell> row{r.method, s.t};
    for (std::size_t i = 0; i < n; ++i) row.emplace_back(s.y[static_cast<Eigen::Index>(i)]);
    row.insert(row.end(), {s.energy, s.dissipated});
    samples.add_row(std::move(row));
  }
  const auto& st = r.stats;
  stats.add_row({r.method, std::string(to_string(r.status)), r.t_reached, st.steps, st.failed_steps,
                 st.rhs_evals, st.jac_evals, st.newton_iters, st.linear_setups, st.root_evals, st.events,
                 st.restarts, st.wall_time_s, st.setup_cpu_s, r.message});
}

}  // namespace contact
