// rigid_impacts: the conservation laws each method keeps exactly, to tolerance, or at first order.
#include "cli_fixture.hpp"

#include <cmath>
#include <map>

namespace {
class RigidImpactsCli : public CliTest {};
}  // namespace

TEST_F(RigidImpactsCli, ConservationErrorsHaveThePredictedSize) {
  const Outcome r = run(RIGID_IMPACTS_EXE, "--out ri");
  ASSERT_EQ(r.code, 0) << r.err;
  std::map<std::string, std::vector<double>> angular;  // "scene method" -> L errors by setting
  for (const auto& c : csv_rows(slurp(dir_ / "ri" / "conservation.csv"))) {
    if (c[0] == "scene") continue;
    const std::string key = c[0] + " " + c[1];
    // Contact forces and impulses come in equal and opposite pairs, and every Runge–Kutta and
    // multistep method keeps linear invariants exactly: only rounding remains.
    EXPECT_LT(std::stod(c[4]), 1e-13) << key << " " << c[3];
    // Impulses act at one point on both bodies with opposite signs: L is kept to rounding.
    if (c[1] == "event-ode" || c[1] == "event-ode-reversed") {
      EXPECT_LT(std::stod(c[5]), 1e-13) << key << " " << c[3];
    }
    angular[key].push_back(std::stod(c[5]));
  }
  // Penalty: L is quadratic, kept only to the tolerance; a 100-fold tighter rtol cuts the spinning
  // box's error at least 10-fold.
  const auto& pen = angular["spinning-box penalty"];
  ASSERT_EQ(pen.size(), 3u);
  EXPECT_LT(pen[1], pen[0] / 10);
  EXPECT_LT(pen[2], pen[1] / 10);
  // Projection moves the wedge's balls by their share of a penetration of at most |v_n| dt, off
  // their lines of momentum: the change in L is first order in dt (ratio 10 within 10%).
  const auto& proj = angular["wedge game-symplectic-projection"];
  ASSERT_EQ(proj.size(), 3u);
  EXPECT_NEAR(proj[0] / proj[1], 10.0, 1.0);
  EXPECT_NEAR(proj[1] / proj[2], 10.0, 1.0);
  EXPECT_TRUE(fs::exists(dir_ / "ri" / "conservation.png"));
}

TEST_F(RigidImpactsCli, BadInputIsRefused) {
  expect_refused(RIGID_IMPACTS_EXE,
                 {
                     {"--dts -1e-4", "--dts", "'-1e-4'", "(0, inf)"},
                     {"--scene rubber-steel", "--scene", "'rubber-steel'", "snooker"},
                     // A step the work limit refuses, before any run: it failed
                     // as 'work-limit' (exit 1) after the 1e-4 s runs, naming no
                     // option. snooker's 0.05 s / 1e8 steps, rounded up.
                     {"--dts 1e-4,1e-300", "--dts", "'1e-300'", "accepted --dts >= 5.01e-10"},
                 });
}
