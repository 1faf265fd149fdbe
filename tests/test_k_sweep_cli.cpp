// The k_sweep experiment: declared outputs, its closed-form numbers checked, bad input refused.
#include "cli_fixture.hpp"

#include <cmath>

namespace {

class KSweepCli : public CliTest {};

}  // namespace

// The Hooke rows have an exact closed form with gravity (references.hpp): penetration and
// duration to the run's accuracy (rtol 1e-10 over ~100 steps: 1e-6 relative). The fitted
// exponents over k >= 1e4 are -1/2 up to gravity's O(g/(wV)) share: within 0.005.
TEST_F(KSweepCli, ReportsClosedFormNumbersAndExponents) {
  const Outcome r = run(K_SWEEP_EXE, "--k-min 1e3 --k-max 1e7 --per-decade 1 --out ks");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto table = csv_rows(slurp(dir_ / "ks" / "k_sweep.csv"));
  ASSERT_EQ(table.front()[0], "k_N_per_m");
  ASSERT_EQ(table.size(), 1 + 3 * 5u);
  int hooke = 0;
  for (std::size_t i = 1; i < table.size(); ++i) {
    if (table[i][1] != "hooke") continue;
    ++hooke;
    EXPECT_NEAR(std::stod(table[i][2]) / std::stod(table[i][3]), 1.0, 1e-6)
        << "penetration at k = " << table[i][0];
    EXPECT_NEAR(std::stod(table[i][4]) / std::stod(table[i][5]), 1.0, 1e-6)
        << "duration at k = " << table[i][0];
    EXPECT_NEAR(std::stod(table[i][6]), 1.0, 1e-6) << "undamped restitution";
  }
  EXPECT_EQ(hooke, 5);
  const auto exps = csv_rows(slurp(dir_ / "ks" / "exponents.csv"));
  ASSERT_EQ(exps.size(), 4u);
  for (std::size_t i = 1; i < exps.size(); ++i) {
    EXPECT_NEAR(std::stod(exps[i][1]), -0.5, 0.005) << exps[i][0];
    EXPECT_NEAR(std::stod(exps[i][3]), -0.5, 0.005) << exps[i][0];
  }
  for (const char* f : {"penetration.png", "penetration.pdf", "duration.png", "cost.png", "stable_dt.png",
                        "meta.json", "k_sweep.md", "k_sweep.tex"})
    EXPECT_TRUE(fs::exists(dir_ / "ks" / f)) << f;
}

// Below k = 33 N/m the first contact outlasted the fixed 1.6 s window and the sweep failed ('no
// complete first bounce'); the window now follows the contact's closed-form duration. At k = 10
// (w = 3.2 rad/s: the contact lasts 1.21 s) the Hooke row still matches its closed form.
TEST_F(KSweepCli, SoftSpringsGetTheTimeTheirContactTakes) {
  const Outcome r = run(K_SWEEP_EXE, "--k-min 10 --k-max 10 --per-decade 1 --out soft");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto table = csv_rows(slurp(dir_ / "soft" / "k_sweep.csv"));
  ASSERT_EQ(table.size(), 1 + 3u);
  for (std::size_t i = 1; i < table.size(); ++i) {
    EXPECT_GT(std::stod(table[i][4]), 1.0) << table[i][1];  // contacts longer than a second
    if (table[i][1] != "hooke") continue;
    EXPECT_NEAR(std::stod(table[i][4]) / std::stod(table[i][5]), 1.0, 1e-6) << "duration";
    EXPECT_NEAR(std::stod(table[i][2]) / std::stod(table[i][3]), 1.0, 1e-6) << "penetration";
  }
}

TEST_F(KSweepCli, BadInputIsRefused) {
  expect_refused(K_SWEEP_EXE, {
                                  {"--k-min 0", "--k-min", "'0'", "(0, inf)"},
                                  {"--k-max -1e5", "--k-max", "'-1e5'", "(0, inf)"},
                                  {"--k-min 1e6 --k-max 1e3", "--k-max", "'1000'", "k-min"},
                                  {"--e 0", "--e", "'0'", "(0, 1]"},
                                  {"--per-decade 0", "--per-decade", "'0'", "[1, 100]"},
                                  // Unbounded, 1e8 per decade allocated 8 GB of k values before a run.
                                  {"--per-decade 100000000", "--per-decade", "'100000000'", "[1, 100]"},
                              });
}
