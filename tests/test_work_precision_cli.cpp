// work_precision: the exact limits its measurements must reach.
#include "cli_fixture.hpp"

#include <cmath>

namespace {

class WorkPrecisionCli : public CliTest {
 protected:
  // error column of the rows matching problem, paradigm and integrator, in order.
  std::vector<double> errors(const std::string& problem, const std::string& paradigm, const std::string& integrator) const {
    std::vector<double> out;
    for (auto& c : csv_rows(slurp(dir_ / "wp" / "work_precision.csv")))
      if (c[0] == problem && c[1] == paradigm && c[2] == integrator) out.push_back(std::stod(c[5]));
    return out;
  }
};

}  // namespace

TEST_F(WorkPrecisionCli, ParadigmsReachTheirExactLimits) {
  const Outcome r = run(WORK_PRECISION_EXE, "--integrators cvode-bdf,rk4 --balls 5 --out wp");
  ASSERT_EQ(r.code, 0) << r.err;
  // The exact flight is the closed form to rounding.
  for (double e : errors("ball", "event", "exact-flight")) EXPECT_LT(e, 1e-14);
  // Equal masses, e = 1: sequential impulses hand the striker's speed to the last ball exactly,
  // whatever the game step or the flight tolerance.
  for (const char* paradigm : {"game", "event"})
    for (const char* integrator : {"semi-implicit-euler", "cvode-bdf"})
      for (double e : errors("chain", paradigm, integrator)) EXPECT_LT(e, 1e-15) << paradigm << " " << integrator;
  // Event-driven CVODE flight: the error follows the tolerance (exponent 1 within 0.1 over 1e-3 .. 1e-9).
  const auto ev = errors("ball", "event", "cvode-bdf");
  ASSERT_EQ(ev.size(), 7u);
  EXPECT_NEAR(std::log(ev.front() / ev.back()) / std::log(1e6), 1.0, 0.1);
  // Penalty under CVODE meets its tolerance against the closed form: within 1000 rtol at 1e-9.
  EXPECT_LT(errors("ball", "penalty", "cvode-bdf").back(), 1000 * 1e-9);
  // rk4 on the chain: fourth order with located switches (4 within 0.5 between the first two steps).
  const auto rk4 = errors("chain", "penalty", "rk4");
  EXPECT_NEAR(std::log2(rk4[0] / rk4[1]), 4.0, 0.5);
  for (const char* f : {"ball_rhs.png", "ball_time.pdf", "chain_rhs.pdf", "chain_time.png"}) EXPECT_TRUE(fs::exists(dir_ / "wp" / f)) << f;
}

TEST_F(WorkPrecisionCli, BadInputIsRefused) {
  expect_refused(WORK_PRECISION_EXE, {
      {"--balls 1", "--balls", "'1'", ">= 2"},
      {"--chain-k -5", "--chain-k", "'-5'", "(0, inf)"},
      {"--problems moon", "--problems", "'moon'", "chain"},
  });
}
