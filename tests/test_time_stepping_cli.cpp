// method_orders and stack, run as a user runs them: the orders time stepping with impacts can
// reach, and the resting column's exact limits.
#include "cli_fixture.hpp"

#include <cmath>
#include <map>
#include <set>

namespace {
class TimeSteppingCli : public CliTest {
 protected:
  // The rows of a CSV as maps from column to cell.
  std::vector<std::map<std::string, std::string>> table(const fs::path& file) const {
    return csv_table(slurp(file));
  }
};
}  // namespace

// Every method here is first order in its smooth part (the Euler family), so no method exceeds
// order 1 by more than the fit's spread over four rows (0.2); the spring methods, which resolve
// the contact in time, reach order 1 (within 0.2) at steps well below the contact time. An
// impulse method resolves each impact inside a step, an O(dt) error in its timing: order <= 1.
TEST_F(TimeSteppingCli, NoTimeSteppingMethodBeatsOrderOneThroughImpacts) {
  const Outcome r = run(
      METHOD_ORDERS_EXE,
      "--methods game-euler,sequential-impulses,soft-step,moreau-jean,xpbd,game-implicit-spring --out mo");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto orders = table(dir_ / "mo" / "orders.csv");
  ASSERT_EQ(orders.size(), 6u);
  for (const auto& row : orders) {
    const double p = std::stod(row.at("fitted_order"));
    EXPECT_LE(p, 1.2) << row.at("method");
    if (row.at("reference") == "spring") {
      EXPECT_NEAR(p, 1.0, 0.2) << row.at("method");
    }
  }
}

// Penalty settles to the static squeeze m g n (n + 1) / (2k) (Kelvin–Voigt damps it within the
// 2 s); Moreau–Jean and event-driven impulses hold the column still (event-driven: its contacts
// start at rest, closed, still and pushed together; they used to end the run as unresolved).
TEST_F(TimeSteppingCli, StackReachesItsExactLimits) {
  const Outcome r = run(STACK_EXE, "--balls 1,4 --methods penalty,moreau-jean,event-ode --out st");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = table(dir_ / "st" / "stack.csv");
  ASSERT_EQ(rows.size(), 6u);
  for (const auto& row : rows) {
    const std::string& method = row.at("method");
    ASSERT_EQ(row.at("status"), "success") << method;
    const double sink = std::stod(row.at("top_sink_m")), exact = std::stod(row.at("closed_form_sink_m"));
    if (method == "penalty")
      EXPECT_NEAR(sink, exact, 1e-6 * exact) << row.at("balls");
    else
      EXPECT_LE(std::abs(sink), 1e-12) << method << " " << row.at("balls");
  }
}

// Under a nonlinear law the methods that need a linear one (xpbd) cannot run the column: 'all'
// (the default) is every method that can, and naming one that cannot is refused in terms of the
// options. The default used to end the run with 'method xpbd cannot run scene ball-stack'.
TEST_F(TimeSteppingCli, StackUnderHertzRunsEveryMethodThatCan) {
  Outcome r = run(STACK_EXE, "--law hertz --balls 1 --t-end 0.05 --out st");
  ASSERT_EQ(r.code, 0) << r.err;
  std::set<std::string> methods;
  for (const auto& row : table(dir_ / "st" / "stack.csv")) methods.insert(row.at("method"));
  EXPECT_TRUE(methods.contains("penalty"));
  EXPECT_TRUE(methods.contains("moreau-jean"));
  EXPECT_FALSE(methods.contains("xpbd"));
  r = run(STACK_EXE, "--law hertz --methods xpbd --out st2");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--methods: value 'xpbd' cannot run with --law hertz"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "st2"));
}

// --k and --law set the penalty law, which the impulse methods do not use: given with only those,
// each is noted (it passed silently), naming what they do read.
TEST_F(TimeSteppingCli, StackNotesALawNoMethodRunUses) {
  const Outcome r =
      run(STACK_EXE, "--methods event-ode,game-euler --k 1e6 --law hertz --balls 1 --t-end 0.05 --out st");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* option : {"--k", "--law"})
    EXPECT_NE(r.err.find(fmt::format(
                  "stack: note: {} has no effect on event-ode, game-euler, which read --dt\n", option)),
              std::string::npos)
        << r.err;
  const Outcome penalty = run(STACK_EXE, "--methods penalty --k 1e6 --balls 1 --t-end 0.05 --out st2");
  ASSERT_EQ(penalty.code, 0) << penalty.err;
  EXPECT_EQ(penalty.err.find("no effect"), std::string::npos) << penalty.err;
}

// method_orders' finest step is bounded by the work it implies, as convergence_dt's: a largest
// step of 8.34e-6 s halved 6 times is 1.2e7 steps to 1.5 s per run (it ran for minutes).
TEST_F(TimeSteppingCli, MethodOrdersRefusesALadderPastTheWorkBound) {
  const Outcome r = run(METHOD_ORDERS_EXE, "--dt-max 8.34e-6 --out mo");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--halvings: value '6'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("accepted [1, 5]"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "mo"));
}
