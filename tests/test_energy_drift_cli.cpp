// energy_drift: the signs and rates of energy error that numerical analysis predicts.
#include "cli_fixture.hpp"
#include "contact_ode/analysis/fit.hpp"

#include <cmath>

namespace {

class EnergyDriftCli : public CliTest {
 protected:
  // Rows of drift.csv for (system, method), in the order of their settings.
  std::vector<std::vector<std::string>> rows(const std::string& system, const std::string& method) const {
    std::vector<std::vector<std::string>> out;
    for (auto& cells : csv_rows(slurp(dir_ / "ed" / "drift.csv")))
      if (cells[0] == system && cells[1] == method) out.push_back(cells);
    return out;
  }
  static double num(const std::vector<std::string>& row, std::size_t col) { return std::stod(row.at(col)); }
  enum Col { kValue = 3, kContacts = 4, kFinal = 5, kMax = 6, kRate = 7, kVerdict = 9 };
};

}  // namespace

TEST_F(EnergyDriftCli, DriftHasThePredictedSignsAndRates) {
  const Outcome r = run(ENERGY_DRIFT_EXE, "--scene snooker,cradle --out ed");
  ASSERT_EQ(r.code, 0) << r.err;
  const double g = 9.81, h0 = 1.0;

  // The exact flight reflects the velocity exactly: 100 impacts, each computed to a few ulps.
  const auto exact = rows("ball", "event-exact");
  ASSERT_EQ(exact.size(), 1u);
  EXPECT_EQ(exact[0][kContacts], "100");
  EXPECT_LT(num(exact[0], kMax), 1e-13);
  EXPECT_EQ(exact[0][kVerdict], "conserves");

  // Explicit Euler gains exactly m g^2 dt^2 / 2 per flight step (a rate of g dt / (2 h0) per second
  // relative to m g h0); projection only lifts the ball and an e = 1 impulse keeps |v|. So the
  // error only grows (its maximum is its final value) at least at that rate, and as a first-order
  // method its rate scales as dt, up to the energy it has added (a factor 1 + final error).
  const auto euler = rows("ball", "game-euler");
  ASSERT_EQ(euler.size(), 2u);
  for (const auto& row : euler) {
    EXPECT_EQ(row[kVerdict], "gains");
    EXPECT_EQ(num(row, kMax), num(row, kFinal));
    EXPECT_GE(num(row, kRate), g * num(row, kValue) / (2 * h0));
  }
  const double ratio = num(euler[0], kRate) / num(euler[1], kRate),
               dt_ratio = num(euler[0], kValue) / num(euler[1], kValue);
  EXPECT_GE(ratio, dt_ratio / (1 + num(euler[1], kFinal)));
  EXPECT_LE(ratio, dt_ratio * (1 + num(euler[0], kFinal)));

  // Explicit Euler on the spring multiplies the contact's energy by 1 + (w dt)^2 every step.
  for (const auto& row : rows("ball", "game-euler-spring")) EXPECT_EQ(row[kVerdict], "gains");

  // Event-driven CVODE flight: the error is CVODE's, proportional to its tolerance: the fitted
  // exponent of |final error| against rtol over 1e-4 .. 1e-8 is 1 within 0.1.
  const auto event = rows("ball", "event-ode");
  ASSERT_EQ(event.size(), 3u);
  const double p = contact::observed_order(num(event[0], kValue), std::abs(num(event[0], kFinal)),
                                           num(event[2], kValue), std::abs(num(event[2], kFinal)));
  EXPECT_NEAR(p, 1.0, 0.1);
  // Penalty: each 100-fold tighter tolerance cuts the error at least 10-fold (an exponent >= 1/2).
  const auto penalty = rows("ball", "penalty");
  ASSERT_EQ(penalty.size(), 3u);
  for (std::size_t i = 0; i + 1 < penalty.size(); ++i)
    EXPECT_LT(std::abs(num(penalty[i + 1], kFinal)), std::abs(num(penalty[i], kFinal)) / 10) << i;

  // Elastic rigid scenes: sequential impulses with e = 1 keep the energy to rounding.
  for (const char* scene : {"snooker", "cradle"})
    for (const char* method : {"event-ode", "event-ode-reversed"}) {
      ASSERT_FALSE(rows(scene, method).empty()) << scene << " " << method;
      for (const auto& row : rows(scene, method)) EXPECT_LT(num(row, kMax), 1e-14) << scene << " " << method;
    }
}

TEST_F(EnergyDriftCli, BadInputIsRefused) {
  expect_refused(ENERGY_DRIFT_EXE,
                 {
                     {"--dts 1e-3,0", "--dts", "'0'", "(0, inf)"},
                     {"--rtols 2", "--rtols", "'2'", "(0, 1)"},
                     {"--bounces 0", "--bounces", "'0'", "[1, 10000]"},
                     // 1e9 bounces failed as 'work-limit', naming no option.
                     {"--bounces 1000000000", "--bounces", "'1000000000'", "[1, 10000]"},
                     {"--scene moon", "--scene", "'moon'", "snooker"},
                     // Runs that could only end in a work limit, refused before any
                     // starts (at 10000 bounces after 42 s of the others): sequential
                     // impulses at dt = 1e-4 s take 10 sweeps a step, 2 t0 / 1e-4 = 9030
                     // steps a bounce, so 1e8 sweeps hold 1107 bounces.
                     {"--bounces 10000", "--bounces", "'10000'", "[1, 1107]"},
                     {"--rigid-dts 1e-9", "--rigid-dts", "'1e-09'", "inf)"},
                     // Not one bounce fits: it blamed --bounces with the empty
                     // range '[1, 0]'. 1e8 sweeps over 2 t0 = 0.903 s at 10
                     // sweeps a step: dt >= 9.03e-8 s, rounded up.
                     {"--dts 1e-9 --bounces 1", "--dts", "'1e-09'", "accepted --dts >= 9.04e-08"},
                 });
}
