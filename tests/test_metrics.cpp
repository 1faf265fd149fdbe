// The metrics every table reports (analysis/metrics.hpp), read off a run built by hand so that each
// quantity's source is known: which contact is the first, which records a maximum runs over, what
// the drift leaves out. (Every other test reads them off simulated runs, where the first contact
// is often the only one and the samples' energy error the largest.) Tolerances: the few roundings
// of numbers of order one that each metric takes (1e-15; 1e-14 where ten joules are subtracted).
#include "contact_ode/analysis/metrics.hpp"
#include "contact_ode/analysis/run_tables.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

using namespace contact;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// E0 = 10 J. The samples lose 0.2 J while the ledger books 0.3 J lost: a drift of -0.1 J at the end.
// The apex's energy is off by 0.5 J, more than any sample's. Two contacts: the first closed (0.1 s,
// 1 mm, in at 4 m/s, out at 3.2), the second deeper and still open.
RunResult booked_run() {
  RunResult r;
  r.energy0 = 10.0;
  r.samples = {
      {0.0, Vector::Zero(2), 10.0, 0.0}, {1.0, Vector::Zero(2), 9.9, 0.05}, {2.0, Vector::Zero(2), 9.8, 0.3}};
  r.apexes = {{.contact = 0, .t = 0.9, .gap = 0.64, .energy = 10.5, .dissipated = 0.05}};
  r.contacts = {
      {.contact = 0, .t_begin = 0.5, .t_end = 0.6, .max_penetration = 1e-3, .v_in = -4.0, .v_out = 3.2},
      {.contact = 0, .t_begin = 1.5, .t_end = kNaN, .max_penetration = 2e-3, .v_in = -3.2, .v_out = kNaN}};
  return r;
}

}  // namespace

TEST(Metrics, EachIsReadFromTheRecordsItNames) {
  const RunMetrics m = compute_metrics(booked_run());
  EXPECT_DOUBLE_EQ(m.max_energy_error, 0.05);  // the apex's 0.5 J, not a sample's 0.2 J
  // |E0 - E - D| / |E0|: 0, 0.005 and 0.01 (the ledger booked more than the samples lost).
  EXPECT_NEAR(m.max_energy_drift, 0.01, 1e-15);
  EXPECT_NEAR(m.final_energy_error, -0.02, 1e-15);
  EXPECT_EQ(m.contacts, 2u);
  EXPECT_DOUBLE_EQ(m.first_penetration, 1e-3);  // the first contact's, not the deepest
  EXPECT_NEAR(m.first_duration, 0.1, 1e-15);
  EXPECT_DOUBLE_EQ(m.first_restitution, 0.8);
  EXPECT_DOUBLE_EQ(m.max_penetration, 2e-3);  // over every contact, the open one too
  EXPECT_DOUBLE_EQ(m.first_apex, 0.64);
}

TEST(Metrics, AnOpenFirstContactHasAPenetrationButNoDurationOrRestitution) {
  RunResult r = booked_run();
  r.contacts.erase(r.contacts.begin());
  const RunMetrics m = compute_metrics(r);
  EXPECT_DOUBLE_EQ(m.first_penetration, 2e-3);
  EXPECT_TRUE(std::isnan(m.first_duration));
  EXPECT_TRUE(std::isnan(m.first_restitution));
  r.contacts.clear();
  r.apexes.clear();
  const RunMetrics none = compute_metrics(r);
  EXPECT_EQ(none.contacts, 0u);
  EXPECT_TRUE(std::isnan(none.first_penetration));
  EXPECT_TRUE(std::isnan(none.first_apex));
  EXPECT_EQ(none.max_penetration, 0.0);
}

// A scene whose initial energy is zero (a ball released at the datum, at rest) has no relative
// scale: its energies are then in joules.
TEST(Metrics, AZeroInitialEnergyMeasuresInJoules) {
  RunResult r = booked_run();
  r.energy0 = 0.0;
  for (auto& s : r.samples) s.energy -= 10.0;
  r.apexes.front().energy -= 10.0;
  const RunMetrics m = compute_metrics(r);
  EXPECT_NEAR(m.max_energy_error, 0.5, 1e-14);
  EXPECT_NEAR(m.max_energy_drift, 0.1, 1e-14);
}

// The gain is the drift's opposite at every sample, and its rate the least-squares slope through
// them: gains 0, -0.005 and +0.01 at t = 0, 1, 2 lie on no line; their slope is 0.005 / s.
TEST(Metrics, TheEnergyGainIsMinusTheDriftAndItsRateTheFittedSlope) {
  const RunResult r = booked_run();
  const EnergyGain g = energy_gain(r);
  const auto drift = energy_drifts(r);
  ASSERT_EQ(g.gain.size(), drift.size());
  for (std::size_t i = 0; i < drift.size(); ++i) EXPECT_EQ(g.gain[i], -drift[i] + 0.0);
  EXPECT_NEAR(g.final_gain, 0.01, 1e-15);
  EXPECT_NEAR(g.rate, 0.005, 1e-15);
  EXPECT_EQ(g.verdict(), "gains");
  EXPECT_EQ(g.verdict(0.02), "conserves");
  const auto apex = apex_energy_errors(r);
  ASSERT_EQ(apex.size(), 1u);
  EXPECT_DOUBLE_EQ(apex.front(), 0.05);
}

namespace {

// A table's cell in `column` of row `row`, as a number (long or double), or NaN if it is text.
double number(const Table& t, std::size_t row, const std::string& column) {
  const auto at = std::find(t.columns().begin(), t.columns().end(), column);
  EXPECT_NE(at, t.columns().end()) << column;
  if (at == t.columns().end()) return kNaN;
  const Table::Cell& cell = t.rows().at(row).at(static_cast<std::size_t>(at - t.columns().begin()));
  if (const auto* l = std::get_if<long>(&cell)) return static_cast<double>(*l);
  if (const auto* d = std::get_if<double>(&cell)) return *d;
  return kNaN;
}

}  // namespace

// Every table a run is written to puts each field under its own column: the run above, its sampled
// state and its solver counts all distinct (1 to 12), read back by column name. (contacts.csv's
// v_in and v_out could be swapped, and the stats' steps with their failures, and no test noticed.)
TEST(RunTables, EachCellIsTheFieldItsColumnNames) {
  RunResult r = booked_run();
  r.method = "m";
  r.t_reached = 2.0;
  r.samples[1].y << 1.5, -2.5;
  SolverStats& st = r.stats;
  st.steps = 1, st.failed_steps = 2, st.rhs_evals = 3, st.jac_evals = 4, st.newton_iters = 5;
  st.linear_setups = 6, st.root_evals = 8, st.events = 9, st.restarts = 10, st.wall_time_s = 11;
  st.setup_cpu_s = 12;
  RunRecords records({"y_m", "v_mps"});
  records.add(r);
  ASSERT_EQ(records.contacts.rows().size(), 2u);
  EXPECT_EQ(number(records.contacts, 0, "t_begin_s"), 0.5);
  EXPECT_EQ(number(records.contacts, 0, "t_end_s"), 0.6);
  EXPECT_EQ(number(records.contacts, 0, "max_penetration_m"), 1e-3);
  EXPECT_EQ(number(records.contacts, 0, "v_in_mps"), -4.0);
  EXPECT_EQ(number(records.contacts, 0, "v_out_mps"), 3.2);
  ASSERT_EQ(records.apexes.rows().size(), 1u);
  EXPECT_EQ(number(records.apexes, 0, "t_s"), 0.9);
  EXPECT_EQ(number(records.apexes, 0, "height_m"), 0.64);
  EXPECT_EQ(number(records.apexes, 0, "energy_J"), 10.5);
  EXPECT_DOUBLE_EQ(number(records.apexes, 0, "energy_change_rel"), 0.05);  // (10.5 - 10) / 10
  ASSERT_EQ(records.samples.rows().size(), 3u);
  EXPECT_EQ(number(records.samples, 1, "t_s"), 1.0);
  EXPECT_EQ(number(records.samples, 1, "y_m"), 1.5);
  EXPECT_EQ(number(records.samples, 1, "v_mps"), -2.5);
  EXPECT_EQ(number(records.samples, 1, "energy_J"), 9.9);
  EXPECT_EQ(number(records.samples, 1, "dissipated_J"), 0.05);
  const std::pair<const char*, double> counts[] = {
      {"t_reached_s", 2}, {"steps", 1},        {"failed_steps", 2},  {"rhs_evals", 3},
      {"jac_evals", 4},   {"newton_iters", 5}, {"linear_setups", 6}, {"root_evals", 8},
      {"events", 9},      {"restarts", 10},    {"wall_time_s", 11},  {"setup_cpu_s", 12}};
  for (const auto& [column, value] : counts) EXPECT_EQ(number(records.stats, 0, column), value) << column;
  // The summary row: metric_cells in metric_columns' order.
  Table summary(metric_columns());
  summary.add_row(metric_cells(r));
  const std::pair<const char*, double> metrics[] = {{"contacts", 2},
                                                    {"first_penetration_m", 1e-3},
                                                    {"first_duration_s", 0.6 - 0.5},
                                                    {"first_restitution", 0.8},
                                                    {"first_apex_m", 0.64},
                                                    {"max_energy_change_rel", 0.05},
                                                    {"energy_drift_rel", 0.01},
                                                    {"steps", 1},
                                                    {"rhs_evals", 3},
                                                    {"jac_evals", 4},
                                                    {"wall_time_s", 11}};
  for (const auto& [column, value] : metrics) EXPECT_NEAR(number(summary, 0, column), value, 1e-15) << column;
}
