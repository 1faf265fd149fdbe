// resting_cost: a penalty contact at rest is stiff — an explicit code's cost per simulated second
// grows as k^(1/2) where the implicit codes' stays flat — and the column rests at its closed-form sag.
#include "cli_fixture.hpp"

#include <cmath>
#include <map>

namespace {

class RestingCostCli : public CliTest {};

}  // namespace

TEST_F(RestingCostCli, AtRestOnlyTheImplicitCodesPayTheSameWhateverK) {
  const Outcome r = run(RESTING_COST_EXE, "--out rc");
  ASSERT_EQ(r.code, 0) << r.err;
  // The implicit codes: the column rings down over a number of its periods set by its damping ratio
  // (fixed by e = 0.5, whatever k), each period followed in a number of steps set by the tolerance,
  // and then rests, which costs them next to nothing: an exponent of 0 (measured -0.11 to -0.05;
  // 0.15 allows for the ring-down's few hundred steps varying with the roots located in it). The
  // explicit one: at rest its step is held at its stability bound, h of order 1 / w_max with w_max
  // ~ 2 sqrt(k / m), so its cost per simulated second grows as k^(1/2) once that bound is below the
  // ring-down's accuracy step; over the whole range, from 1e5, by less (measured 0.42).
  auto exponents = csv_table(slurp(dir_ / "rc" / "exponents.csv"));
  ASSERT_EQ(exponents.size(), 4u);
  for (auto row : exponents) {
    const double p = std::stod(row["rhs_exponent"]);
    if (row["kind"] == "implicit") {
      EXPECT_LT(std::abs(p), 0.15) << row["integrator"];
    } else {
      EXPECT_GT(p, 0.3) << row["integrator"];
    }
  }
  // The stiff end, k = 1e6 ... 1e8: the explicit code's slope is the stability bound's 1/2 (measured
  // 0.47; the bound's constant shifts with the mode the rounding excites, within 0.1 of it).
  std::map<std::string, std::map<double, double>> rhs;
  for (auto& row : csv_table(slurp(dir_ / "rc" / "cost.csv"))) {
    rhs[row["integrator"]][std::stod(row["k_N_per_m"])] = std::stod(row["rhs_per_sim_s"]);
    // Every code rests at the springs' static sag m g n (n + 1) / (2 k) to the order of its tolerance:
    // 1e-4 relative is a hundred times rtol, what the ring-down's few thousand steps can accumulate
    // (measured 1.3e-6 at most, cvode-adams at 1e7).
    EXPECT_NEAR(std::stod(row["top_sink_m"]), std::stod(row["closed_form_sink_m"]),
                1e-4 * std::stod(row["closed_form_sink_m"]))
        << row["integrator"] << " k = " << row["k_N_per_m"];
  }
  ASSERT_EQ(rhs["arkode-erk"].size(), 4u);
  const double slope = std::log(rhs["arkode-erk"][1e8] / rhs["arkode-erk"][1e6]) / std::log(100.0);
  EXPECT_NEAR(slope, 0.5, 0.1);
  // And where it rests stiffly the explicit code pays more than every implicit one (25 to 190 times
  // at k = 1e8, measured).
  for (const char* name : {"cvode-bdf", "cvode-adams", "arkode-dirk"})
    EXPECT_GT(rhs["arkode-erk"][1e8], 10 * rhs[name][1e8]) << name;
  for (const char* f : {"rhs.png", "rhs.pdf", "cost.tex", "exponents.md"})
    EXPECT_TRUE(fs::exists(dir_ / "rc" / f)) << f;
}

TEST_F(RestingCostCli, BadInputIsRefused) {
  expect_refused(RESTING_COST_EXE, {
                                       {"--k-min 1e5 --k-max 1e3", "--k-max", "'1000'", "[k-min, inf)"},
                                       {"--integrators rk4", "--integrators", "'rk4'", "adaptive"},
                                       {"--rtol 1", "--rtol", "'1'", "(1e-12, 0.01)"},
                                       {"--balls 0", "--balls", "'0'", "[1, 1000]"},
                                       {"--t-end 0", "--t-end", "'0'", "(0.001, 100)"},
                                   });
}
