// The metrics every table reports (analysis/metrics.hpp), read off a run built by hand so that each
// quantity's source is known: which contact is the first, which records a maximum runs over, what
// the drift leaves out. (Every other test reads them off simulated runs, where the first contact
// is often the only one and the samples' energy error the largest.) Tolerances: the few roundings
// of numbers of order one that each metric takes (1e-15; 1e-14 where ten joules are subtracted).
#include "contact_ode/analysis/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

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
