// engines: what the README and the paper say of the engines, read from the experiment's tables.
#include "cli_fixture.hpp"
#include "contact_ode/integrators/method_registry.hpp"

#include <cmath>
#include <map>
#include <set>

namespace {

class EnginesCli : public CliTest {
 protected:
  // Rows of a CSV as column -> cell maps.
  std::vector<std::map<std::string, std::string>> table(const std::string& file) const {
    return csv_table(slurp(dir_ / "eng" / file));
  }
  std::map<std::string, std::string> row(const std::string& scene, const std::string& method) const {
    for (auto& r : table("engines.csv"))
      if (r["scene"] == scene && r["method"] == method) return r;
    ADD_FAILURE() << "no row " << scene << " " << method;
    return {};
  }
  static double num(const std::string& s) { return s == "nan" || s.empty() ? std::nan("") : std::stod(s); }
};

}  // namespace

TEST_F(EnginesCli, TheEnginesAsTheReadmeDescribesThem) {
  const Outcome r = run(ENGINES_EXE, "--repeats 1 --out eng");
  ASSERT_EQ(r.code, 0) << r.err;
  const double dt = 1e-3, V = std::sqrt(2 * 9.81), e = 0.8;
  // Newton's law within the step: Bullet tuned and ODE's first apex within (1 + e^2) V dt of e^2 h0
  // (test_engines derives it); Bullet at its defaults misses that bound.
  for (const char* method : {"bullet-tuned", "ode", "ode-quick"})
    EXPECT_LT(num(row("drop", method)["scored_error"]), (1 + e * e) * V * dt) << method;
  EXPECT_GT(num(row("drop", "bullet")["scored_error"]), (1 + e * e) * V * dt);
  // At smaller steps Bullet's defaults stop bouncing at all: no apex at dt / 2 and dt / 4.
  for (auto& c : table("convergence.csv"))
    if (c["method"] == "bullet" && num(c["dt_s"]) < dt) {
      EXPECT_TRUE(std::isnan(num(c["apex_error_m"]))) << c["dt_s"];
    }
  // MuJoCo at its defaults (solref 0.02, dampratio 1): the ball does not bounce.
  EXPECT_EQ(row("drop", "mujoco")["contacts"], "1");
  EXPECT_TRUE(std::isnan(num(row("drop", "mujoco")["scored_error"])));
  // Siconos event-driven: the exact bounce, to its integrator's tolerance.
  EXPECT_LT(num(row("drop", "siconos")["scored_error"]), 1e-8);
  // ODE's dWorldStep stops on contacts that touch at rest, as a typed failure; its QuickStep runs them.
  for (const char* scene : {"cradle-0", "stack"}) {
    EXPECT_EQ(row(scene, "ode")["status"], "solver-error") << scene;
    EXPECT_EQ(row(scene, "ode-quick")["status"], "success") << scene;
  }
  // ODE's spring is implicit Euler: at w dt = 0.32 the drop's first restitution is 0.58 for the
  // law's 0.8 (as the README says; implicit Euler's damping, not the law's, takes the rest).
  EXPECT_NEAR(num(row("drop", "ode-spring")["first_restitution"]), 0.58, 0.005);
  // MuJoCo's spring on the column of 0.1 kg balls at w dt = 1.41 chatters: more than ten times
  // the four contacts it has.
  EXPECT_GT(num(row("stack", "mujoco-spring")["contacts"]), 40);
  EXPECT_NEAR(num(row("stack", "mujoco-spring")["omega_dt"]), std::sqrt(1e5 * 20) * dt, 1e-9);
  // The drift is how far an engine strays from Newton's law: MuJoCo's default contact keeps none of
  // the e^2 E0 that law keeps at the first bounce, within the soft contact's sink m g d / E0 = d / h0
  // (d its largest penetration, 3.2 cm).
  const double h0 = 1.0, sink = num(row("drop", "mujoco")["max_penetration_m"]) / h0;
  EXPECT_NEAR(num(row("drop", "mujoco")["energy_drift_rel"]), e * e, sink);
  // Bullet's defaults feed their Baumgarte push-out into a touching row struck at e = 1, tuned not.
  EXPECT_GT(num(row("cradle-0", "bullet")["energy_drift_rel"]), 0.1);
  EXPECT_LT(num(row("cradle-0", "bullet-tuned")["energy_drift_rel"]), 0.01);
  // The scores are against the exact answers: the head-on pair's Newton velocities (1 -+ e) v0 / 2,
  // which one contact under sequential impulses, Moreau-Jean and Siconos' LCP gives to rounding
  // (test_time_stepping derives the first two), and the column's static sink m g n (n + 1) / 2k at
  // the top, which the penalty column, settled by its dashpots in 2 s, reaches to rounding too
  // (1e-15 m of a 1e-4 m sink); the impulse methods hold it unsunk.
  for (const char* method : {"sequential-impulses", "moreau-jean", "siconos"})
    EXPECT_LT(num(row("head-on", method)["scored_error"]), 1e-15) << method;
  for (const char* method : {"penalty", "sequential-impulses", "moreau-jean"})
    EXPECT_LT(num(row("stack", method)["scored_error"]), 1e-15) << method;
  for (const char* f : {"engines.md", "orders.csv", "work_precision.png", "work_precision.pdf"})
    EXPECT_TRUE(fs::exists(dir_ / "eng" / f)) << f;
}

TEST_F(EnginesCli, BadInputIsRefused) {
  expect_refused(ENGINES_EXE, {{"--dt 0", "--dt", "'0'", "(0, inf)"},
                               {"--repeats 0", "--repeats", "'0'", "[1, 1000]"},
                               {"--k -1", "--k", "'-1'", "(0, inf)"}});
}

// A step so short that every fixed-step run exceeds its work limit at once: each is a row with its
// status, and the work-precision figure, with no point to draw, says so. Its bare "plot " used to
// be a gnuplot error that ended the experiment (exit 1, "function to plot expected").
TEST_F(EnginesCli, ASweepWithoutAPointStillDrawsItsFigure) {
  const Outcome r = run(ENGINES_EXE, "--dt 1e-12 --repeats 1 --out eng");
  ASSERT_EQ(r.code, 0) << r.err;
  std::set<std::string> scenes, limited;  // every scene, and those with a work-limited fixed-step row
  for (auto& row : table("engines.csv"))
    if (contact::method_info(row["method"]).fixed_step) {
      EXPECT_EQ(row["status"], "work-limit") << row["scene"] << " " << row["method"];
      limited.insert(row["scene"]);
    }
  for (auto& row : table("engines.csv")) scenes.insert(row["scene"]);
  ASSERT_EQ(scenes.size(), 5u);  // drop, head-on, cradle-1mm, cradle-0, stack
  EXPECT_EQ(limited, scenes);
  EXPECT_NE(slurp(dir_ / "eng" / "work_precision.gp").find("nothing to draw"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "eng" / "work_precision.png"));
}
