// contact_cost: a resolved penalty contact is not stiff — the cost per contact of every adaptive
// code, explicit or implicit, is flat in k — and the paper's reading of it, from the tables.
#include "cli_fixture.hpp"

#include <cmath>
#include <map>

namespace {

class ContactCostCli : public CliTest {};

}  // namespace

TEST_F(ContactCostCli, EveryAdaptiveCodePaysTheSamePerContactWhateverK) {
  const Outcome r = run(CONTACT_COST_EXE, "--per-decade 1 --out cc");
  ASSERT_EQ(r.code, 0) << r.err;
  auto exponents = csv_table(slurp(dir_ / "cc" / "exponents.csv"));
  ASSERT_EQ(exponents.size(), 6u);
  bool explicit_seen = false;
  for (auto row : exponents) {
    // A code whose step were bounded by stability in the contact would pay steps ~ w ~ k^(1/2): an
    // exponent of 1/2 (and 2 * 10^4 times more from 1e2 to 1e10). Every code here follows the
    // contact's own time scale with a number of steps set by the tolerance: below 0.05 (measured
    // 0.015 at most), the cost varying by less than a factor of two over eight decades of k.
    EXPECT_LT(std::abs(std::stod(row["rhs_exponent"])), 0.05) << row["integrator"];
    EXPECT_LT(std::stod(row["rhs_max"]), 2 * std::stod(row["rhs_min"])) << row["integrator"];
    explicit_seen |= row["kind"] == "explicit";
  }
  EXPECT_TRUE(explicit_seen);
  // Accuracy is the tolerance's, whatever k: the first apex within 1e3 rtol for every code. (CPU
  // times per contact are reported, not asserted: speed belongs in the benchmarks.)
  std::map<double, std::map<std::string, contact::CsvRecord>> by_k;
  for (auto& row : csv_table(slurp(dir_ / "cc" / "cost.csv")))
    by_k[std::stod(row["k_N_per_m"])][row["integrator"]] = row;
  ASSERT_EQ(by_k.size(), 9u);
  for (auto& [k, rows] : by_k)
    for (auto& [name, row] : rows)
      EXPECT_LT(std::stod(row["first_apex_error_m"]), 1e3 * 1e-8) << name << " k = " << k;
  for (const char* f : {"rhs.png", "cpu.pdf", "cost.tex", "exponents.md"})
    EXPECT_TRUE(fs::exists(dir_ / "cc" / f)) << f;
}

// A soft spring (k = 10 N/m: the contact lasts 1.2 s) outlasted the fixed 1.6 s window and the run
// failed with 'no complete first bounce'; the window now follows the contact, and the first apex
// (no energy is lost: at h0) is within 1e3 rtol as at every other k.
TEST_F(ContactCostCli, SoftSpringsGetTheTimeTheirContactTakes) {
  const Outcome r =
      run(CONTACT_COST_EXE, "--k-min 10 --k-max 10 --integrators cvode-bdf,gsl-rk8pd --out soft");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = csv_table(slurp(dir_ / "soft" / "cost.csv"));
  ASSERT_EQ(rows.size(), 2u);
  for (auto row : rows) EXPECT_LT(std::stod(row["first_apex_error_m"]), 1e3 * 1e-8) << row["integrator"];
}

// An undamped spring never holds the ball, but a loose tolerance can: on k = 0.002 N/m (a contact
// of 138 s) at rtol 5.6e-3, arkode-erk's error leaves the ball below the spring's sag with too little
// energy to come back. The program read the missing first apex and crashed (SIGSEGV); it now fails
// saying why, and leaves no output.
TEST_F(ContactCostCli, AnIntegratorsErrorThatHoldsTheBallFailsTheRunSayingSo) {
  const Outcome r =
      run(CONTACT_COST_EXE,
          "--k-min 0.002047 --k-max 0.002047 --rtol 0.005639 --integrators arkode-erk --out held");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("arkode-erk at k = 0.002047: no first apex by t = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the integrator's error held the ball on it; tighten --rtol"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "held"));
}

TEST_F(ContactCostCli, BadInputIsRefused) {
  expect_refused(CONTACT_COST_EXE, {
                                       {"--k-min 1e5 --k-max 1e3", "--k-max", "'1000'", "[k-min, inf)"},
                                       {"--integrators rk4", "--integrators", "'rk4'", "adaptive"},
                                       {"--rtol 1", "--rtol", "'1'", "(1e-12, 0.01)"},
                                       {"--per-decade 1000", "--per-decade", "'1000'", "[1, 100]"},
                                   });
}
