// convergence_k and zeno: their numbers against the closed forms they have.
#include "cli_fixture.hpp"
#include "contact_ode/analysis/table.hpp"

#include <cmath>
#include <map>

namespace {

class ConvergenceExperimentsCli : public CliTest {};

// The rows of a CSV keyed by their first cell.
std::map<std::string, std::vector<std::string>> by_first(const std::string& csv) {
  std::map<std::string, std::vector<std::string>> out;
  for (auto& cells : csv_rows(csv)) out[cells.front()] = cells;
  return out;
}

}  // namespace

// The penalty bounce times and apex heights close on the rigid ones as k^(-1/2) (contact time
// pi sqrt(m/k); gravity's O(g/(wV)) shift of restitution): fitted exponents within 0.01, and the
// local order between the last two rows within 0.005 (the O(1/k) corrections have faded).
TEST_F(ConvergenceExperimentsCli, ConvergenceKFindsTheHalfOrder) {
  const Outcome r = run(CONVERGENCE_K_EXE, "--k-min 1e4 --k-max 1e8 --out ck");
  ASSERT_EQ(r.code, 0) << r.err;
  auto rates = by_first(slurp(dir_ / "ck" / "rates.csv"));
  EXPECT_NEAR(std::stod(rates["impact_time_error"][1]), -0.5, 0.01);
  EXPECT_NEAR(std::stod(rates["apex_height_error"][1]), -0.5, 0.01);
  auto rows = by_first(slurp(dir_ / "ck" / "convergence_k.csv"));
  const auto& last = rows["100000000"];
  EXPECT_NEAR(std::stod(last[2]), -0.5, 0.005);
  EXPECT_NEAR(std::stod(last[4]), -0.5, 0.005);
  EXPECT_TRUE(fs::exists(dir_ / "ck" / "errors.png"));
}

// Zeno (the paper's Zeno section: the study runs these defaults): the event-driven runs stop within the
// rest criterion's reach of t_inf (bounces slower than the 1e-3 m/s criterion last at most
// 2e-3/(g(1-e)) = 1e-3 s in all, plus one 1 ms sample); the exact flight makes
// ceil(log(1e-7/V)/log e) = 79 impacts before its 1e-7 m/s guard, the last 2 t0 e^79 / (1 - e)
// before t_inf (its impact times are sums of 79 flights, each rounded to half an ulp of 4 s: 3.5e-14
// at most); the flight under CVODE ends where its rest height, 100 atol = 1e-8 m, does, within the
// guards' bound 2 v_rest / (g (1 - e)) of t_inf, v_rest = sqrt(2 g 1e-8); the penalty and game-spring
// balls settle at the static deflection -m g / k; nothing falls through the floor deeper than the
// first contact's penetration (V sqrt(m/k) = 0.014 m at k = 1e5).
TEST_F(ConvergenceExperimentsCli, ZenoStopsAtTheAccumulationAndNothingFallsThrough) {
  const Outcome r = run(ZENO_EXE, "--out zn");
  ASSERT_EQ(r.code, 0) << r.err;
  std::map<std::string, contact::CsvRecord> rows;
  for (auto& row : contact::read_csv(dir_ / "zn" / "zeno.csv")) rows[row.at("method")] = row;
  const auto at = [&](const char* method, const char* column) { return std::stod(rows[method].at(column)); };
  const double g = 9.81, e = 0.8, t0 = std::sqrt(2 / g), t_inf = t0 * (1 + e) / (1 - e);
  for (const char* m : {"event-exact", "event-ode"}) {
    EXPECT_LE(at(m, "rest_time_s"), t_inf + 1e-3) << m;
    EXPECT_GE(at(m, "rest_time_s"), t_inf - 2.1e-3) << m;
    EXPECT_EQ(at(m, "final_height_m"), 0.0) << m << " rests on the floor";
  }
  EXPECT_EQ(rows["event-exact"].at("contacts"), "79");
  EXPECT_NEAR(at("event-exact", "last_contact_before_zeno_s"), 2 * t0 * std::pow(e, 79) / (1 - e), 1e-13);
  const double ode_gap = at("event-ode", "last_contact_before_zeno_s");
  EXPECT_GT(ode_gap, 0.0);
  EXPECT_LE(ode_gap, 2 * std::sqrt(2 * g * 1e-8) / (g * (1 - e)));
  for (const char* m : {"penalty", "game-symplectic-spring"})
    EXPECT_NEAR(at(m, "final_height_m"), -g / 1e5, 1e-7) << m << " ends at the static deflection";
  for (const char* m : {"event-exact", "event-ode", "penalty", "game-symplectic", "game-symplectic-spring"})
    EXPECT_GE(at(m, "min_height_m"), -std::sqrt(2 * g) * std::sqrt(1 / 1e5)) << m;
}

// Soft springs ended the experiment with exit 1. At k = 10 N/m (sag 0.98 m) the ball is held for
// good in its second contact: a row that says so, with no errors. At k = 50 N/m its contacts
// (0.45 s each) push the third apex past the rigid ball's span; the run now takes the longer span
// it needs, and its errors are the k^(-1/2) law's: the local order from 50 to 500 N/m is -1/2
// within gravity's share g / (w V) at the third impact (V = e^2 sqrt(2 g h0): 0.16 at k = 500).
TEST_F(ConvergenceExperimentsCli, ConvergenceKRecordsSoftSpringsThatHoldOrSlowTheBall) {
  Outcome r = run(CONVERGENCE_K_EXE, "--k-min 10 --k-max 100 --per-decade 1 --out held");
  ASSERT_EQ(r.code, 0) << r.err;
  auto rows = csv_rows(slurp(dir_ / "held" / "convergence_k.csv"));
  ASSERT_EQ(rows.size(), 1 + 2u);
  EXPECT_EQ(rows[1].back(), "held in contact 2");
  EXPECT_TRUE(std::isnan(std::stod(rows[1][1])));
  EXPECT_EQ(rows[2].back(), "ok");
  r = run(CONVERGENCE_K_EXE, "--k-min 50 --k-max 500 --per-decade 1 --out slow");
  ASSERT_EQ(r.code, 0) << r.err;
  rows = csv_rows(slurp(dir_ / "slow" / "convergence_k.csv"));
  ASSERT_EQ(rows.size(), 1 + 2u);
  EXPECT_EQ(rows[1].back(), "ok") << "k = 50 compares its three bounces";
  const double share = 9.81 / (std::sqrt(500.0) * 0.64 * std::sqrt(2 * 9.81));
  EXPECT_NEAR(std::stod(rows[2][2]), -0.5, share) << "impact times";
  EXPECT_NEAR(std::stod(rows[2][4]), -0.5, share) << "apex heights";
}

TEST_F(ConvergenceExperimentsCli, BadInputIsRefused) {
  expect_refused(
      CONVERGENCE_K_EXE,
      {
          // Values printed in full: at 6 digits both read '1e+06', a refusal that contradicted itself.
          {"--k-min 1000001 --k-max 1000000.5", "--k-max", "'1000000.5' is not above --k-min = 1000001",
           "(k-min, inf)"},
          {"--bounces 0", "--bounces", "'0'", ">= 1"},
          {"--per-decade 1000", "--per-decade", "'1000'", "[1, 100]"},
          // At e = 0.05 the rigid ball rests after 5 apexes (e^n V < 1e-7 m/s): more bounces failed
          // with 'did not reach the bounces'.
          {"--e 0.05 --bounces 6", "--bounces", "'6'", "[1, 5]"},
          // Not one apex: it blamed --bounces with the empty range '[1, 0]'. An apex needs
          // e V >= 1e-7 m/s, V = sqrt(2 g h0) = 4.43 m/s: e >= 2.258e-8, rounded up.
          {"--e 1e-300 --bounces 1", "--e", "'1e-300'", "accepted --e >= 2.26e-08"},
      });
  expect_refused(ZENO_EXE, {
                               {"--e 1", "--e", "'1'", "(0, 1)"},
                               {"--t-end -6", "--t-end", "'-6'", "(0, 10000)"},
                               // every run failed at t = 0 on the 1 ms samples it may keep (exit 1)
                               {"--t-end 1e300", "--t-end", "'1e300'", "(0, 10000)"},
                               // 1e13 game steps: refused at t = 0 after the other runs' half a
                               // minute, exit 1; now before any run (9999 s / 1e8 steps).
                               {"--t-end 9999 --dt 1e-9", "--dt", "'1e-09'", "accepted --dt >= 0.0001"},
                           });
}
