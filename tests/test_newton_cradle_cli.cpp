// newton_cradle: the exchange laws the cradle must obey.
#include "cli_fixture.hpp"

#include <cmath>

namespace {
class NewtonCradleCli : public CliTest {};
}  // namespace

TEST_F(NewtonCradleCli, ImpulsesExchangeExactlyAndSpringsConserveMomentumAndEnergy) {
  const Outcome r = run(NEWTON_CRADLE_EXE, "--balls 5 --out nc");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = csv_rows(slurp(dir_ / "nc" / "velocities.csv"));
  ASSERT_EQ(rows.size(), 1 + 4 * 6u);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& c = rows[i];
    const std::string method = c[0];
    const double spacing = std::stod(c[1]);
    double momentum = 0;
    for (int b = 0; b < 5; ++b) momentum += std::stod(c[2 + b]);
    // Every method conserves momentum: impulses exactly, springs to the solver's tolerance.
    EXPECT_NEAR(momentum, 1.0, 1e-8) << method << " " << spacing;
    if (method == "event" || method == "game") {
      // Equal masses, e = 1: each impulse swaps two velocities, so the last ball leaves at 1 m/s
      // and the others stop, exactly.
      for (int b = 0; b < 4; ++b) EXPECT_EQ(std::stod(c[2 + b]), 0.0) << method << " " << spacing << " ball " << b;
      EXPECT_EQ(std::stod(c[6]), 1.0) << method << " " << spacing;
    } else {
      // Undamped springs keep the energy to CVODE's tolerance (rtol 1e-10, a few hundred steps).
      EXPECT_LT(std::abs(std::stod(c[8])), 1e-6) << method << " " << spacing;
      // A gap of 1 mm exceeds both springs' compression (linear: v sqrt(m/2k) = 0.22 mm), so the
      // collisions are binary and each is an exact exchange: the last ball carries all the energy.
      if (spacing == 1e-3) {
        EXPECT_NEAR(std::stod(c[7]), 1.0, 1e-6) << method;
      }
    }
  }
  EXPECT_TRUE(fs::exists(dir_ / "nc" / "energy_share.png"));
}

TEST_F(NewtonCradleCli, BadInputIsRefused) {
  expect_refused(NEWTON_CRADLE_EXE, {
      {"--balls 1", "--balls", "'1'", "[2, 1000]"},
      {"--balls 10000000", "--balls", "'10000000'", "[2, 1000]"},
      {"--spacings 0,-1e-3", "--spacings", "'-1e-3'", "[0, inf)"},
      {"--dt 0", "--dt", "'0'", "(0, inf)"},
  });
}
