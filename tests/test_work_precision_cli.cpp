// work_precision: the exact limits its measurements must reach.
#include "cli_fixture.hpp"
#include "contact_ode/analysis/fit.hpp"

#include <cmath>

using contact::observed_order;

namespace {

class WorkPrecisionCli : public CliTest {
 protected:
  struct Point {
    double value, error;  // the step or tolerance, and the error
  };
  // The rows matching problem, paradigm and integrator, in order.
  std::vector<Point> points(const std::string& problem, const std::string& paradigm,
                            const std::string& integrator) const {
    std::vector<Point> out;
    for (auto& c : csv_rows(slurp(dir_ / "wp" / "work_precision.csv")))
      if (c[0] == problem && c[1] == paradigm && c[2] == integrator)
        out.push_back({std::stod(c[4]), std::stod(c[5])});
    return out;
  }
};

}  // namespace

TEST_F(WorkPrecisionCli, ParadigmsReachTheirExactLimits) {
  const Outcome r = run(WORK_PRECISION_EXE, "--integrators cvode-bdf,rk4 --balls 5 --out wp");
  ASSERT_EQ(r.code, 0) << r.err;
  // The exact flight is the closed form to rounding.
  for (const auto& p : points("ball", "event", "exact-flight")) EXPECT_LT(p.error, 1e-14);
  // Equal masses, e = 1: sequential impulses hand the striker's speed to the last ball exactly,
  // whatever the game step or the flight tolerance.
  for (const char* paradigm : {"game", "event"})
    for (const char* integrator : {"semi-implicit-euler", "cvode-bdf"})
      for (const auto& p : points("chain", paradigm, integrator))
        EXPECT_LT(p.error, 1e-15) << paradigm << " " << integrator;
  // Event-driven CVODE flight: the error follows the tolerance (exponent 1 within 0.1 from the
  // loosest to the tightest).
  const auto ev = points("ball", "event", "cvode-bdf");
  ASSERT_GE(ev.size(), 2u);
  EXPECT_NEAR(observed_order(ev.front().value, ev.front().error, ev.back().value, ev.back().error), 1.0, 0.1);
  // Penalty under CVODE meets its tolerance against the closed form: within 1000 rtol at the
  // tightest (the global error of a few hundred steps, each controlled to rtol).
  const auto bdf = points("ball", "penalty", "cvode-bdf");
  EXPECT_LT(bdf.back().error, 1000 * bdf.back().value);
  // rk4 on the chain: fourth order with located switches (4 within 0.5 between the first two steps).
  const auto rk4 = points("chain", "penalty", "rk4");
  ASSERT_GE(rk4.size(), 2u);
  EXPECT_NEAR(observed_order(rk4[0].value, rk4[0].error, rk4[1].value, rk4[1].error), 4.0, 0.5);
  // The SciPy peer on the same ball, scored against the same closed form: every method meets
  // its tolerance as CVODE does (within 1000 rtol at the tightest), and tightening the tolerance
  // from 1e-3 to 1e-9 gains at least three orders.
  for (const char* method : {"BDF", "Radau", "LSODA", "RK45"}) {
    const auto peer = points("ball", "scipy", method);
    ASSERT_EQ(peer.size(), 7u) << method;
    EXPECT_LT(peer.back().error, 1000 * peer.back().value) << method;
    EXPECT_LT(peer.back().error, 1e-3 * peer.front().error) << method;
  }
  for (const char* f : {"ball_rhs.png", "ball_time.pdf", "chain_rhs.pdf", "chain_time.png"})
    EXPECT_TRUE(fs::exists(dir_ / "wp" / f)) << f;
}

TEST_F(WorkPrecisionCli, BadInputIsRefused) {
  expect_refused(WORK_PRECISION_EXE, {
                                         {"--balls 1", "--balls", "'1'", ">= 2"},
                                         {"--chain-k -5", "--chain-k", "'-5'", "(0, inf)"},
                                         {"--problems moon", "--problems", "'moon'", "chain"},
                                     });
}
