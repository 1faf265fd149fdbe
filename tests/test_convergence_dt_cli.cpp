// convergence_dt: the order drop through the force's kink and its recovery with located switches.
#include "cli_fixture.hpp"

#include <cmath>
#include <map>
#include <tuple>

namespace {

class ConvergenceDtCli : public CliTest {
 protected:
  // The last row (finest step or tightest tolerance) of an integrator: {step or rtol, error}.
  std::pair<double, double> finest_row(const std::string& table, const std::string& integrator,
                                       const std::string& events) const {
    std::pair<double, double> row{std::nan(""), std::nan("")};
    for (auto& cells : csv_rows(slurp(dir_ / "cd" / (table + ".csv"))))
      if (cells[0] == integrator && cells[1] == events) row = {std::stod(cells[2]), std::stod(cells[3])};
    return row;
  }
  double finest(const std::string& table, const std::string& integrator, const std::string& events) const {
    return finest_row(table, integrator, events).second;
  }
};

}  // namespace

TEST_F(ConvergenceDtCli, LocatedSwitchesRestoreTheOrderTheKinkTakes) {
  const Outcome r =
      run(CONVERGENCE_DT_EXE,
          "--integrators euler,semi-implicit-euler,velocity-verlet,rk4,gsl-rkf45,cvode-bdf --out cd");
  ASSERT_EQ(r.code, 0) << r.err;
  std::map<std::string, contact::CsvRecord> o;
  for (auto& row : csv_table(slurp(dir_ / "cd" / "orders.csv"))) o[row["integrator"]] = row;
  const auto num = [&](const std::string& name, const char* column) { return std::stod(o[name][column]); };
  // Located: every switch is a step end and the method shows its order p over the fit's range
  // (the five finest rows with 1e-9 < max error < 1e-2, max over three drop heights, so over the
  // kinks' phases in the step); 0.3 covers what is left of the pre-asymptotic spread.
  for (const char* name : {"velocity-verlet", "gsl-rkf45"})
    EXPECT_NEAR(num(name, "fixed_order_located"), num(name, "order"), 0.3) << name;
  // RK4 located converges faster than dt^4 above the floor (measured 6.0): its amplitude error per
  // contact step is (w dt)^6 / 144, fifth order over a contact, and dominates its fourth-order phase
  // error, which only shifts the exit and enters scaled by V / (w h0) = 0.044.
  EXPECT_GE(num("rk4", "fixed_order_located"), 4 - 0.3);
  // Semi-implicit Euler is conjugate to Stormer-Verlet: its first-order error is a bounded offset
  // (v off by g dt / 2) that does not grow, so over these steps the second-order error of the
  // contacts dominates (measured 1.97). Between its order and Verlet's:
  EXPECT_GE(num("semi-implicit-euler", "fixed_order_located"), 1 - 0.3);
  EXPECT_LE(num("semi-implicit-euler", "fixed_order_located"), 2 + 0.3);
  // Explicit Euler never reaches the fit's range here: each contact multiplies its energy by about
  // exp(pi w dt), and its flight errs g t dt / 2; at the finest step (w dt = 0.003) the error is
  // still above 1e-2, so no order is fitted rather than a pre-asymptotic one.
  EXPECT_GT(finest("fixed_step", "euler", "located"), 1e-2);
  EXPECT_TRUE(std::isnan(num("euler", "fixed_order_located")));
  // Unlocated, a method of order p > 2 drops to 2: a step across the kink of F = k max(-x, 0)
  // integrates a force with a jump in slope, O(dt^2) per crossing; the maximum over the kinks'
  // phases makes that the fitted slope (measured 2.29 for rk4, 1.76 for rkf45).
  for (const char* name : {"rk4", "gsl-rkf45"}) {
    EXPECT_EQ(num(name, "expected_unlocated"), 2) << name;
    EXPECT_NEAR(num(name, "fixed_order_unlocated"), 2, 0.5) << name;
  }
  // At the finest step (w dt = 0.003) the unlocated error ~ (w dt)^-2 ~ 1e5 times the located one
  // for a method of order >= 4; 100x is asserted (the located ladders stop earlier, at the round-off
  // floor, below the unlocated errors of every step).
  EXPECT_GT(finest("fixed_step", "rk4", "unlocated"), 100 * finest("fixed_step", "rk4", "located"));
  EXPECT_GT(finest("fixed_step", "gsl-rkf45", "unlocated"),
            100 * finest("fixed_step", "gsl-rkf45", "located"));
  // CVODE with located switches meets its tolerance in proportion: at the tightest rtol its worst
  // drop errs 2.8e-7 = 2800 rtol (about 300 steps, each controlling its local error to rtol, whose
  // errors add in the worst case, on a state whose velocity reaches V = 4.4 m/s). Below 1e4 rtol
  // is asserted: a broken error control or a missed switch costs orders of magnitude more.
  const auto [rtol, error] = finest_row("adaptive", "cvode-bdf", "located");
  EXPECT_LT(error, 1e4 * rtol);
  // The paper's advice, read from the tables: locating the switches makes velocity Verlet, RK4 and
  // RKF45 more accurate at every step and at every tolerance tighter than 1e-3 (at 1e-3 RKF45 errs
  // by ~4 % either way, and which is ahead depends on the steps' luck); semi-implicit Euler at fewer than
  // half of its steps; CVODE BDF, whose error control already sees the kink, at no more than 3 of its 8
  // tolerances more than it loses (measured 4 of 8), while it costs fewer evaluations.
  const auto errors = [&](const std::string& table, const std::string& integrator,
                          const std::string& events) {
    std::vector<double> out;
    for (auto& row : csv_table(slurp(dir_ / "cd" / (table + ".csv"))))
      if (row["integrator"] == integrator && row["events"] == events)
        out.push_back(std::stod(row["error_max"]));
    return out;
  };
  // Rows from `first` on (the adaptive table's first row is rtol 1e-3), as far as both ladders go: a
  // fixed-step ladder stops at its first error below the round-off floor (1e-9), which the located
  // one of a high-order method reaches while the unlocated one, held to order 2 by the kink, is far above.
  const auto located_better = [&](const std::string& table, const std::string& integrator,
                                  std::size_t first = 0) {
    const auto located = errors(table, integrator, "located"),
               unlocated = errors(table, integrator, "unlocated");
    EXPECT_LE(located.size(), unlocated.size()) << integrator;
    if (located.size() < unlocated.size()) {
      EXPECT_LT(located.back(), 1e-9) << integrator;
    }
    if (unlocated.size() < located.size()) {
      EXPECT_LT(unlocated.back(), 1e-9) << integrator;
    }
    const std::size_t both = std::min(located.size(), unlocated.size());
    std::size_t better = 0;
    for (std::size_t i = first; i < both; ++i) better += located[i] < unlocated[i];
    return std::pair{better, both - std::min(first, both)};
  };
  for (const auto& [table, name, first] : {std::tuple{"fixed_step", "velocity-verlet", 0},
                                           {"fixed_step", "rk4", 0},
                                           {"fixed_step", "gsl-rkf45", 0},
                                           {"adaptive", "gsl-rkf45", 1}}) {
    const auto [better, rows] = located_better(table, name, first);
    EXPECT_EQ(better, rows) << name;
    EXPECT_GE(rows, 5u) << name;  // RK4's located ladder reaches the floor at its fifth step
  }
  // A fixed-step ladder stops at its first error below the round-off floor, 1e-9: RK4 located reaches
  // it at dt = 1.25e-4 s (measured 3.4e-10; 1.4e-9 the step before); unlocated it runs every step.
  const auto rk4 = errors("fixed_step", "rk4", "located");
  ASSERT_GE(rk4.size(), 2u);
  EXPECT_LT(rk4.back(), 1e-9);
  EXPECT_GE(rk4[rk4.size() - 2], 1e-9);
  EXPECT_EQ(errors("fixed_step", "rk4", "unlocated").size(), 7u);
  const auto [better, rows] = located_better("fixed_step", "semi-implicit-euler");
  EXPECT_LT(2 * better, rows);
  const auto [bdf_better, bdf_rows] = located_better("adaptive", "cvode-bdf");
  EXPECT_LT(bdf_better, bdf_rows);
  EXPECT_LT(num("cvode-bdf", "rhs_evals_tightest_located"), num("cvode-bdf", "rhs_evals_tightest_unlocated"));
  for (const char* figure :
       {"fixed_located.png", "fixed_unlocated.pdf", "adaptive_located.png", "adaptive_unlocated.pdf"})
    EXPECT_TRUE(fs::exists(dir_ / "cd" / figure)) << figure;
}

TEST_F(ConvergenceDtCli, BadInputIsRefused) {
  expect_refused(CONVERGENCE_DT_EXE,
                 {
                     {"--dt-max 2", "--dt-max", "'2'", "(0, t-final)"},
                     {"--halvings 0", "--halvings", "'0'", ">= 1"},
                     {"--integrators rk5", "--integrators", "'rk5'", "rk4"},
                     {"--tol-min 1e-20", "--tol-min", "'1e-20'", "[1e-14, 0.0001]"},
                     {"--heights 0", "--heights", "'0'", "[1, 100]"},
                     // 2e-3 s / 2^40 to 1.5 s: 8e14 steps, past the runs' 1e7.
                     {"--halvings 40", "--halvings", "'40'", "[1, 13]"},
                     // A largest step whose run alone takes 1.5e9 steps: no count
                     // is, and it blamed --halvings. Halved once, the sweep's least:
                     // 2 x 1.5 s / 1e7 steps.
                     {"--dt-max 1e-9", "--dt-max", "'1e-09'", "accepted: a largest step >= 3e-07 s"},
                 });
}

// A run that fails is a row with its status, not the end of the study. ARKODE's SDIRK at a fixed
// step w dt = 1.6 (k = 6.27e5 N/m, dt = 2 ms): with located switches every stage is an affine
// equation in one contact mode, which Newton's method solves in one iteration; unlocated, the mode
// follows each iterate, and at one of the three heights the iteration across the kink of
// F = k max(-x, 0) fails and the fixed step cannot be shortened. That row used to end the whole
// experiment (exit 1, no tables).
TEST_F(ConvergenceDtCli, AFailedRunIsARowNotTheEnd) {
  const Outcome r =
      run(CONVERGENCE_DT_EXE, "--integrators arkode-dirk --k 6.27e5 --halvings 1 --tol-min 1e-4 --out cd");
  ASSERT_EQ(r.code, 0) << r.err;
  std::map<std::pair<std::string, std::string>, contact::CsvRecord> rows;  // [events, dt]
  for (auto& row : csv_table(slurp(dir_ / "cd" / "fixed_step.csv"))) rows[{row["events"], row["dt_s"]}] = row;
  ASSERT_EQ(rows.size(), 4u);
  const auto& failed = rows[{"unlocated", "0.002"}];
  EXPECT_EQ(failed.at("status"), "convergence-failure");
  EXPECT_TRUE(std::isnan(std::stod(failed.at("error_max"))));
  EXPECT_NE(r.err.find("arkode-dirk unlocated (dt 0.002): convergence-failure at t = "), std::string::npos)
      << r.err;
  // The located rows at the same steps ran, and halving the step cuts the error by 2^3 or more:
  // SDIRK is of order 4, and at w dt = 1.6 its leading term does not dominate yet (measured 3.5).
  const auto located = [&](const char* dt) { return rows[{"located", dt}]; };
  for (const char* dt : {"0.002", "0.001"}) EXPECT_EQ(located(dt).at("status"), "ok") << dt;
  EXPECT_GT(std::stod(located("0.002").at("error_max")), 8 * std::stod(located("0.001").at("error_max")));
  // The failed row is no point of the fits: the unlocated fixed order has one row left, no fit.
  const auto orders = csv_table(slurp(dir_ / "cd" / "orders.csv"));
  ASSERT_EQ(orders.size(), 1u);
  EXPECT_TRUE(std::isnan(std::stod(orders[0].at("fixed_order_unlocated"))));
}
