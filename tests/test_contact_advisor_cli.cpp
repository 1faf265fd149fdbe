// The contact_advisor executable's contract: non-physical requests are refused with the option,
// the value and the accepted range (exit 2, nothing written); a request writes its table.
#include "cli_fixture.hpp"

namespace {

class ContactAdvisorCli : public CliTest {};

}  // namespace

TEST_F(ContactAdvisorCli, NonPhysicalRequestsAreRefused) {
  expect_refused(
      CONTACT_ADVISOR_EXE,
      {
          {"--v -5 --max-penetration 1e-3", "--v", "'-5'", "(0, inf)"},
          {"--v 0 --max-penetration 1e-3", "--v", "'0'", "(0, inf)"},
          {"--e 1.5 --max-penetration 1e-3", "--e", "'1.5'", "[0, 1]"},
          // In full: at 6 digits it read "value '1' is out of range; accepted range [1, 1]".
          {"--e 0.999999999 --law hooke --max-penetration 1e-3", "--e", "'0.999999999'", "[1, 1] for hooke"},
          {"--e nan --max-penetration 1e-3", "--e", "'nan'", "[0, 1]"},
          {"--max-penetration 0", "--max-penetration", "'0'", "(0, inf)"},
          {"--max-penetration -1e-3", "--max-penetration", "'-1e-3'", "(0, inf)"},
          {"--duration -2", "--duration", "'-2'", "(0, inf)"},
          {"--m 0 --duration 1e-3", "--m", "'0'", "(0, inf)"},
          {"--law hertz --radius 0.01 --young 2e11 --poisson 0.5", "--poisson", "'0.5'", "(-1, 0.5)"},
          {"--law hertz --radius 0.01 --young 2e11 --poisson -1", "--poisson", "'-1'", "(-1, 0.5)"},
          {"--law hooke --e 0.8 --max-penetration 1e-3", "--e", "'0.8'", "[1, 1]"},
          {"--law kelvin-voigt-clamped --e 0.1 --max-penetration 1e-3", "--e", "'0.1'", "0.1353"},
          {"--law jelly --max-penetration 1e-3", "--law", "'jelly'", "hertz"},
          {"--max-penetration 1e-3 --duration 1e-3", "--max-penetration", "", "exactly one"},
          // A damping rule with a law that has none was silently ignored (the same advice as without).
          {"--law kelvin-voigt --rule flores --max-penetration 1e-3", "--rule", "'flores'",
           "--law hertz or hunt-crossley-linear"},
      });
}

TEST_F(ContactAdvisorCli, WritesTheAdviceTable) {
  const Outcome r = run(CONTACT_ADVISOR_EXE, "--m 1 --v 5 --e 0.8 --max-penetration 1e-3 --out advice");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = slurp(dir_ / "advice" / "advice.csv");
  EXPECT_EQ(csv.rfind("quantity,value,unit,note", 0), 0u);
  for (const char* q : {"ode_erp", "mujoco_timeconst", "box2d_hertz", "drake_penetration_allowance",
                        "achieved_penetration", "achieved_restitution", "symplectic_max_dt", "game_dt"})
    EXPECT_NE(csv.find(q), std::string::npos) << q;
  EXPECT_TRUE(fs::exists(dir_ / "advice" / "meta.json"));
}

// MuJoCo's solref = (timeconst, dampratio) sets b = 2 / timeconst and k = 1 / (timeconst dampratio)^2:
// an undamped contact (Hooke, e = 1) is timeconst = inf at dampratio 0, which the table gave as
// 'inf' with the note for a damped one. Its note now points to the direct form, whose stiffness is
// k / m (1e6 1/s^2 for a 1 mm penetration at 1 m/s: k = m v^2 / x^2).
TEST_F(ContactAdvisorCli, AnUndampedContactsSolrefIsTheDirectForm) {
  const Outcome r =
      run(CONTACT_ADVISOR_EXE, "--m 1 --v 1 --e 1 --law hooke --max-penetration 1e-3 --out advice");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = slurp(dir_ / "advice" / "advice.csv");
  EXPECT_NE(
      csv.find(
          "mujoco_timeconst,inf,s,\"solref[0]: none for an undamped contact; use solref = (-stiffness, 0)\""),
      std::string::npos)
      << csv;
  EXPECT_NE(csv.find("mujoco_stiffness,1000000"), std::string::npos) << csv;
}

// The README's worked question is the program's answer, as printed.
TEST_F(ContactAdvisorCli, TheReadmeSampleIsWhatItPrints) {
  const Outcome r = run(CONTACT_ADVISOR_EXE, "--m 1 --v 5 --e 0.8 --max-penetration 1e-3");
  ASSERT_EQ(r.code, 0) << r.err;
  expect_readme_sample(slurp(README), "It then checks itself by simulating the contact", r.out, {});
}
