// The contact_laws experiment: its table and figure exist and parse, its Kelvin–Voigt rows hit
// their targets (closed form: the dashpot formula is exact without gravity), and bad input is
// refused.
#include "cli_fixture.hpp"
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/models/contact_law.hpp"

#include <cmath>

namespace {
class ContactLawsCli : public CliTest {};
}  // namespace

TEST_F(ContactLawsCli, WritesTableAndFigureWithTheDeclaredColumns) {
  const Outcome r = run(CONTACT_LAWS_EXE, "--points 4 --out laws");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = slurp(dir_ / "laws" / "restitution.csv");
  EXPECT_EQ(csv.rfind("law,target_e,achieved_e,miss\n", 0), 0u);
  // 12 laws (Kelvin-Voigt, clamped, five rules x two exponents) x 4 targets + header.
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 49);
  for (const char* f : {"restitution.png", "restitution.pdf", "restitution.gp", "restitution.md",
                        "restitution.tex", "meta.json"})
    EXPECT_GT(fs::file_size(dir_ / "laws" / f), 100u) << f;
  EXPECT_EQ(slurp(dir_ / "laws" / "restitution.png").substr(1, 3), "PNG");
  EXPECT_EQ(slurp(dir_ / "laws" / "restitution.pdf").substr(0, 4), "%PDF");
  // kelvin-voigt,0.5,<achieved>,<miss>: the miss is at the simulation's accuracy (1e-6).
  std::istringstream lines(csv);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("kelvin-voigt,", 0) != 0) continue;
    const double miss = std::stod(line.substr(line.rfind(',') + 1));
    EXPECT_LT(std::abs(miss), 1e-6) << line;
  }
}

// The Hunt–Crossley family, F = K delta^n (1 + chi delta_dot), has an exact restitution that
// depends on chi V alone (hunt_crossley_restitution, derived in references.hpp). The experiment's
// rows (CVODE, rtol 1e-10) must match it to 1e-7: the exact rule's rows miss their targets by up
// to 4e-9 (the run's error accumulated over a contact's steps), so 1e-7 leaves 25 times that.
TEST_F(ContactLawsCli, HuntCrossleyRowsMatchTheExactRestitution) {
  const Outcome r = run(CONTACT_LAWS_EXE, "--points 4 --out laws");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<std::pair<std::string, contact::DampingRule>> rules = {
      {"hunt-crossley", contact::DampingRule::HuntCrossley},
      {"lankarani-nikravesh", contact::DampingRule::LankaraniNikravesh},
      {"flores", contact::DampingRule::Flores},
      {"gonthier", contact::DampingRule::Gonthier},
      {"exact", contact::DampingRule::Exact}};
  int checked = 0;
  for (const auto& c : csv_rows(slurp(dir_ / "laws" / "restitution.csv"))) {
    for (const auto& [name, rule] : rules) {
      if (c[0].rfind(name + " n=", 0) != 0) continue;
      const double target = std::stod(c[1]), achieved = std::stod(c[2]);
      const double a = contact::damping_factor(rule, target, 1.0) * 1.0;  // chi V at the default V = 1 m/s
      const double e = contact::hunt_crossley_restitution(a);
      EXPECT_NEAR(achieved, e, 1e-7) << c[0] << " target " << target;
      if (rule == contact::DampingRule::Exact) {
        EXPECT_NEAR(achieved, target, 1e-7) << c[0];
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 40);  // 5 rules x 2 exponents x the 4 targets of --points 4
}

TEST_F(ContactLawsCli, BadInputIsRefused) {
  expect_refused(CONTACT_LAWS_EXE, {
                                       {"--v -1", "--v", "'-1'", "(0, inf)"},
                                       {"--m 0", "--m", "'0'", "(0, inf)"},
                                       {"--depth nan", "--depth", "'nan'", "(0, inf)"},
                                       {"--points 1", "--points", "'1'", "[2, 1000]"},
                                       // Unbounded, 1e9 points ran for hours.
                                       {"--points 1e9", "--points", "'1e9'", "[2, 1000]"},
                                       // Each in range, together a stiffness of 0 or inf: the law
                                       // refused it naming its own K, exit 1.
                                       {"--v 1e-300", "--v", "'1e-300'", "normal range"},
                                       {"--depth 1e-300", "--depth", "'1e-300'", "normal range"},
                                   });
}
