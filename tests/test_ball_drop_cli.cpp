// The ball_drop executable's contract: bad input -> one line naming the option, the value and
// the accepted range, exit code 2, no output; success -> every declared file with its columns.
#include "cli_fixture.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/method_registry.hpp"

#include <regex>
#include <set>

#include <nlohmann/json.hpp>

namespace {

class BallDropCli : public CliTest {
 protected:
  Outcome run(const std::string& args) const { return CliTest::run(BALL_DROP_EXE, args); }
};

}  // namespace

TEST_F(BallDropCli, BadInputIsRefusedWithOptionValueAndRangeAndWritesNothing) {
  const std::vector<BadInput> cases = {
      {"--k 0", "--k", "'0'", "(0, inf)"},
      {"--k -1e5", "--k", "'-1e5'", "(0, inf)"},
      {"--k nan", "--k", "'nan'", "(0, inf)"},
      {"--k inf", "--k", "'inf'", "(0, inf)"},
      {"--k 1e5x", "--k", "'1e5x'", "(0, inf)"},
      {"--m 0", "--m", "'0'", "(0, inf)"},
      {"--m -2", "--m", "'-2'", "(0, inf)"},
      {"--g -9.81", "--g", "'-9.81'", "[0, inf)"},
      {"--h0 0", "--h0", "'0'", "(0, inf)"},
      {"--dt 0", "--dt", "'0'", "(0, inf)"},
      {"--dt -1e-3", "--dt", "'-1e-3'", "(0, inf)"},
      {"--e 1.01", "--e", "'1.01'", "[0, 1]"},
      {"--e -0.1", "--e", "'-0.1'", "[0, 1]"},
      {"--e NaN", "--e", "'NaN'", "[0, 1]"},
      // A Hunt-Crossley law tuned to e = 0 has infinite damping: every penalty run failed at the
      // first touch, its right-hand side not finite (exit 1, 'CV_FIRST_RHSFUNC_ERR').
      {"--law hertz --e 0", "--e", "'0'", "(0, 1]"},
      {"--law hunt-crossley-linear --e 0", "--e", "'0'", "(0, 1]"},
      {"--rtol 0", "--rtol", "'0'", "(0, 1)"},
      {"--atol -1e-9", "--atol", "'-1e-9'", "[0, inf)"},
      {"--t-end 0", "--t-end", "'0'", "(0, inf)"},
      {"--t-end ten", "--t-end", "'ten'", "(0, inf)"},
      {"--v0 nan", "--v0", "'nan'", "(-inf, inf)"},
      {"--max-steps 0", "--max-steps", "'0'", ">= 1"},
      {"--method warp-drive", "--method", "'warp-drive'", "event-exact"},
      {"--method penalty,,game-euler", "--method", "''", "penalty"},
      {"--law rubber", "--law", "'rubber'", "kelvin-voigt"},
      {"--bogus 3", "--bogus", "", "--help"},
      {"--sweep --k-min 1e6 --k-max 1e3", "--k-max", "'1000'", "k-min"},
      // Unbounded, 1e8 points per decade took 24 GB before the first run.
      {"--sweep --per-decade 100000000", "--per-decade", "'100000000'", "[1, 100]"},
      {"--integrator warp", "--integrator", "'warp'", "cvode-bdf"},
      {"--linear-solver cholesky", "--linear-solver", "'cholesky'", "klu"},
      {"--integrator gsl-rk8pd --linear-solver klu", "--linear-solver", "'klu'", "implicit SUNDIALS methods"},
      {"--jacobian exact", "--jacobian", "'exact'", "analytic, dq"},
      // A drop beyond the doubles was refused as "--atol: value 'inf'" (an atol derived from the
      // height scale) or, with --atol, as "linear_law_first_contact: V = inf".
      {"--v0 1e300", "--v0", "'1e+300'", "both finite"},
      {"--v0 -1e160 --atol 1e-9", "--v0", "'-1e+160'", "both finite"},
      // The impact speed overflows through g alone; the refusal named --h0 and --v0 only.
      {"--g 1e308", "--g", "'1e+308'", "both finite"},
      // More output samples than a run keeps: every method failed at t = 0 (exit 1, a row each).
      {"--sample-dt 1e-300", "--sample-dt", "'1e-300'", "--sample-dt > --t-end / 10000000 = 3e-07"},
      {"--t-end 1e300", "--t-end", "'1e+300'", "--sample-dt > --t-end / 10000000"},
      // The bound itself is refused (its grid has one point more than is kept), so the accepted
      // range is open: it read ">= ... = 1e-09" while refusing 1e-09.
      {"--t-end 0.01 --sample-dt 1e-9", "--sample-dt", "'1e-09'", "--sample-dt > --t-end / 10000000 = 1e-09"},
  };
  expect_refused(BALL_DROP_EXE, cases);
}

TEST_F(BallDropCli, OutputThatIsAFileIsRefused) {
  std::ofstream(dir_ / "taken") << "x";
  const Outcome r = run("--out taken");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'taken'"), std::string::npos) << r.err;
}

TEST_F(BallDropCli, HelpListsEveryOptionWithDefaultAndRange) {
  const Outcome r = run("--help");
  EXPECT_EQ(r.code, 0);
  for (const char* s :
       {"--method", "--law", "--k FLOAT:in (0, inf)=100000", "--e FLOAT:in [0, 1]=0.8", "--integrator",
        "--linear-solver", "arkode-imex", "gmres-band", "--m", "--g", "--h0", "--dt", "--rtol", "--atol",
        "--t-end", "--out", "--sweep", "event-exact", "game-symplectic-spring"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
  EXPECT_TRUE(dir_is_empty());
}

TEST_F(BallDropCli, SolverFailureExitsOneWithStatusTimeAndMessageAndWritesNothing) {
  const Outcome r = run("--method penalty --k 1e8 --max-steps 5 --sample-dt 1 --out results");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("max-steps at t = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("CV_TOO_MUCH_WORK"), std::string::npos) << r.err;
  EXPECT_TRUE(dir_is_empty());
}

TEST_F(BallDropCli, SuccessfulRunWritesEveryDeclaredFileWithItsColumns) {
  const Outcome r = run("--t-end 1 --out results");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<std::pair<std::string, std::string>> files = {
      {"contacts.csv", "method,t_begin_s,t_end_s,max_penetration_m,v_in_mps,v_out_mps"},
      {"apexes.csv", "method,t_s,height_m,energy_J,energy_change_rel"},
      {"samples.csv", "method,t_s,y_m,v_mps,energy_J,dissipated_J"},
      {"stats.csv",
       "method,status,t_reached_s,steps,failed_steps,rhs_evals,jac_evals,newton_iters,"
       "linear_setups,root_evals,events,restarts,wall_time_s,setup_cpu_s,message"},
      {"comparison.csv", "method,status,contacts,first_penetration_m"},
  };
  for (const auto& [name, header] : files) {
    const std::string text = slurp(dir_ / "results" / name);
    EXPECT_EQ(text.rfind(header, 0), 0u) << name << " starts with: " << text.substr(0, 120);
    EXPECT_GT(std::count(text.begin(), text.end(), '\n'), 1) << name << " has no rows";
  }
  for (const char* name : {"comparison.md", "comparison.tex"})
    EXPECT_TRUE(fs::exists(dir_ / "results" / name)) << name;
  const auto meta = nlohmann::json::parse(slurp(dir_ / "results" / "meta.json"));
  EXPECT_EQ(meta["experiment"], "ball_drop");
  EXPECT_EQ(meta["options"]["t-end"], "1");
  EXPECT_EQ(meta["options"]["k"], "100000");
  EXPECT_TRUE(meta["libraries"].contains("sundials"));
  // Taken at build time from this checkout (cmake/git_revision.cmake): git describe, 12 hex digits.
  const std::string revision = meta["git_revision"];
  EXPECT_TRUE(std::regex_match(revision, std::regex("(.+-g)?[0-9a-f]{12}(-dirty)?"))) << revision;
  for (const auto& e : fs::directory_iterator(dir_ / "results"))
    EXPECT_EQ(e.path().extension() == ".tmp", false) << "left a temporary file " << e.path();
}

TEST_F(BallDropCli, SweepPrintsOneRowPerStiffnessAndMethod) {
  const Outcome r = run("--sweep --k-min 1e2 --k-max 1e4 --t-end 1 --out sweep");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = slurp(dir_ / "sweep" / "sweep.csv");
  // 3 stiffnesses x the methods the penalty law affects (penalty, penalty-dq, the spring game
  // loops, xpbd, the engines' spring settings) + one row for each of the others, plus the header.
  long dependent = 0, independent = 0;
  for (const auto& m : contact::method_registry()) (m.uses_contact_law ? dependent : independent) += 1;
  EXPECT_GE(dependent, 6);
  EXPECT_GE(independent, 9);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3 * dependent + independent + 1) << csv;
  EXPECT_EQ(csv.rfind("k_N_per_m,method,omega_dt,closed_form_penetration_m,closed_form_duration_s,status", 0),
            0u);
}

// The README's reading of the default sweep (k = 1e2 ... 1e8, dt = 1 ms): CVODE's cost per run stays
// between 500 and 1000 right-hand sides across the six decades (an error-controlled step follows
// the contact, whose steps per contact do not depend on k); explicit Euler's spring gains energy
// in a contact (restitution above 1) from w dt = 0.3 on, its (1 + w^2 dt^2) growth per step; the
// semi-implicit spring keeps the ball's restitution below 1 up to its stability bound w dt = 2
// and gains energy beyond it.
TEST_F(BallDropCli, TheDefaultSweepReadsAsTheReadmeSays) {
  const Outcome r = run("--sweep --out full");
  ASSERT_EQ(r.code, 0) << r.err;
  int penalty = 0, euler = 0, symplectic = 0;
  for (const auto& row : contact::read_csv(dir_ / "full" / "sweep.csv")) {
    const std::string& method = row.at("method");
    const double omega_dt = std::stod(row.at("omega_dt")), e = std::stod(row.at("first_restitution"));
    if (method == "penalty") {
      ++penalty;
      EXPECT_GE(std::stod(row.at("rhs_evals")), 500) << row.at("k_N_per_m");
      EXPECT_LE(std::stod(row.at("rhs_evals")), 1000) << row.at("k_N_per_m");
    } else if (method == "game-euler-spring" && omega_dt >= 0.3) {
      ++euler;
      EXPECT_GT(e, 1.0) << "w dt = " << omega_dt;
    } else if (method == "game-symplectic-spring") {
      ++symplectic;
      EXPECT_EQ(e > 1.0, omega_dt > 2) << "w dt = " << omega_dt << ", restitution " << e;
    }
  }
  // The default sweep: k = 1e2 ... 1e8, one a decade (7 rows); w dt = sqrt(k) 1e-3 >= 0.3 from 1e5 (4).
  EXPECT_EQ(penalty, 7);
  EXPECT_EQ(euler, 4);
  EXPECT_EQ(symplectic, 7);
}

// Without gravity a ball at rest (or thrown up) never reaches the floor: every method runs to the
// end with no contact. The closed-form first contact printed after the table was then asked for
// an impact at 0 m/s, and the run ended with exit 2, 'linear_law_first_contact: V = 0 is out of
// range', after every method had run, and wrote nothing.
TEST_F(BallDropCli, ABallThatNeverReachesTheFloorIsARunWithoutContacts) {
  for (const char* args : {"--g 0", "--g 0 --v0 1"}) {
    const Outcome r = run(std::string(args) + " --t-end 0.5 --out still");
    ASSERT_EQ(r.code, 0) << args << ": " << r.err;
    const auto rows = contact::read_csv(dir_ / "still" / "comparison.csv");
    EXPECT_GE(rows.size(), 15u) << args;
    for (const auto& row : rows) {
      EXPECT_EQ(row.at("status"), "success") << args << " " << row.at("method");
      EXPECT_EQ(row.at("contacts"), "0") << args << " " << row.at("method");
    }
    EXPECT_EQ(r.out.find("closed-form first contact"), std::string::npos) << args;
  }
}

// With a power law (Hertz) there is no linear spring for XPBD or an engine's spring setting to
// match: "all" is every method that can run that ball, and the others are left out, not failed.
TEST_F(BallDropCli, AllMeansTheMethodsTheLawAllows) {
  const Outcome r = run("--law hertz --t-end 0.6 --out hz");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string csv = slurp(dir_ / "hz" / "comparison.csv");
  EXPECT_NE(csv.find("\npenalty,"), std::string::npos) << csv;
  for (const char* absent : {"\nxpbd,", "\nmujoco-spring,", "\node-spring,"})
    EXPECT_EQ(csv.find(absent), std::string::npos) << absent;
}

// rtol given with a fixed-step integrator changes nothing (no error control): the run says so on
// stderr, as co.solve() warns in Python, and runs bitwise the same; an adaptive integrator given
// one, or atol (the contact threshold and the event-driven rest height), says nothing.
TEST_F(BallDropCli, AToleranceAFixedStepIntegratorIgnoresIsNoted) {
  const std::string base = "--method penalty --integrator rk4 --dt 1e-4 --t-end 0.6";
  const Outcome with = run(base + " --rtol 1e-3 --out with");
  ASSERT_EQ(with.code, 0) << with.err;
  EXPECT_NE(with.err.find("--rtol has no effect on --integrator rk4"), std::string::npos) << with.err;
  const Outcome without = run(base + " --out without");
  ASSERT_EQ(without.code, 0) << without.err;
  EXPECT_EQ(without.err.find("no effect"), std::string::npos) << without.err;
  EXPECT_EQ(slurp(dir_ / "with" / "samples.csv"), slurp(dir_ / "without" / "samples.csv"));
  for (const char* quiet :
       {"--method penalty --t-end 0.6 --rtol 1e-9 --out adaptive",
        "--method penalty --integrator rk4 --dt 1e-4 --t-end 0.6 --atol 1e-9 --out atol"}) {
    const Outcome r = run(quiet);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err.find("no effect"), std::string::npos) << quiet << ": " << r.err;
  }
}

// A method setting that none of the methods run reads is noted with what they do read, as co.solve()
// warns: --method siconos --integrator rk4 said nothing, and with --rtol blamed rk4, which siconos
// does not run. The sweep runs the methods --method names (it ran every method whatever it said).
TEST_F(BallDropCli, AnOptionNoMethodRunReadsIsNoted) {
  const Outcome engine = run("--method siconos --integrator rk4 --rtol 1e-6 --t-end 0.2 --out engine");
  ASSERT_EQ(engine.code, 0) << engine.err;
  EXPECT_NE(engine.err.find("note: --integrator has no effect on siconos, which reads --dt\n"),
            std::string::npos)
      << engine.err;
  EXPECT_NE(engine.err.find("note: --rtol has no effect on siconos, which reads --dt\n"), std::string::npos)
      << engine.err;
  EXPECT_EQ(engine.err.find("on --integrator rk4"), std::string::npos) << engine.err;
  const Outcome two = run("--method game-euler,event-exact --jacobian dq --dt 1e-3 --t-end 0.2 --out two");
  ASSERT_EQ(two.code, 0) << two.err;
  EXPECT_NE(two.err.find(
                "note: --jacobian has no effect on game-euler, event-exact, which read --dt, --rest-speed\n"),
            std::string::npos)
      << two.err;
  EXPECT_EQ(two.err.find("--dt has no effect"), std::string::npos) << two.err;  // game-euler reads it
  const Outcome law = run("--method event-exact --k 1e3 --law hertz --t-end 0.2 --out law");
  ASSERT_EQ(law.code, 0) << law.err;
  EXPECT_NE(law.err.find("note: --k has no effect on event-exact, which reads --rest-speed\n"),
            std::string::npos)
      << law.err;
  EXPECT_NE(law.err.find("note: --law has no effect on event-exact"), std::string::npos) << law.err;
  const Outcome sweep =
      run("--sweep --method penalty,event-exact --k-min 1e3 --k-max 1e4 --t-end 0.3 --out sweep");
  ASSERT_EQ(sweep.code, 0) << sweep.err;
  std::multiset<std::string> methods;
  for (const auto& row : contact::read_csv(dir_ / "sweep" / "sweep.csv")) methods.insert(row.at("method"));
  EXPECT_EQ(methods, (std::multiset<std::string>{"penalty", "penalty", "event-exact"}));
}

// The other mode's options do nothing: a sweep's k range without --sweep, --k in a sweep. They
// were silently ignored (a user asking for --k-min 10 got one run at --k); now each is noted.
TEST_F(BallDropCli, TheOtherModesOptionsAreNoted) {
  const Outcome single = run("--method penalty --t-end 0.1 --k-min 10 --per-decade 3 --out single");
  ASSERT_EQ(single.code, 0) << single.err;
  EXPECT_NE(single.err.find("--k-min has no effect without --sweep"), std::string::npos) << single.err;
  EXPECT_NE(single.err.find("--per-decade has no effect without --sweep"), std::string::npos) << single.err;
  EXPECT_EQ(single.err.find("--k-max"), std::string::npos) << single.err;
  const Outcome sweep = run("--method penalty --t-end 0.1 --sweep --k-min 1e4 --k-max 1e4 --k 5 --out sweep");
  ASSERT_EQ(sweep.code, 0) << sweep.err;
  EXPECT_NE(sweep.err.find("--k has no effect with --sweep"), std::string::npos) << sweep.err;
  const Outcome plain = run("--method penalty --t-end 0.1 --k 1e4 --out plain");
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_EQ(plain.err.find("no effect"), std::string::npos) << plain.err;
}

// The closed-form first contact is exact with gravity: where a soft damped spring holds the ball
// for good (k = 10 N/m, e = 0.3: the oscillation about the sag never returns to zero overlap) it
// says so, as the run's first contact never ends, rather than "duration inf s" (or, before the
// closed form took gravity, a gravity-free duration of 1.1 s for a contact that does not end).
TEST_F(BallDropCli, AContactTheSpringHoldsForGoodIsSaidToBeUnending) {
  const Outcome r = run("--method penalty --law kelvin-voigt --k 10 --e 0.3 --out held");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("closed-form first contact at k = 10: unending (the spring holds the ball), max "
                       "penetration 1.64788 m"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("| penalty | success | 1        | 1.648               | —"), std::string::npos)
      << r.out;
}

// The README's sample output is the program's: every cell but the wall times.
TEST_F(BallDropCli, TheReadmeSampleIsWhatItPrints) {
  const Outcome r = run("");
  ASSERT_EQ(r.code, 0) << r.err;
  expect_readme_sample(slurp(README), "as printed by the study command", r.out, {"wall_time_s"});
}

// --jacobian is the Jacobian of the implicit integrators, penalty's included (penalty-dq always
// forms difference quotients): penalty ignored it and ran with the analytic one, bitwise the same
// run as without it. Given dq, penalty is penalty-dq.
TEST_F(BallDropCli, PenaltyTakesTheJacobianItIsGiven) {
  const Outcome dq = run("--method penalty,penalty-dq --jacobian dq --t-end 0.6 --out dq");
  ASSERT_EQ(dq.code, 0) << dq.err;
  const Outcome analytic = run("--method penalty --t-end 0.6 --out analytic");
  ASSERT_EQ(analytic.code, 0) << analytic.err;
  auto row = [&](const char* folder, const char* method) {
    for (const auto& r : contact::read_csv(dir_ / folder / "stats.csv"))
      if (r.at("method") == method) return r;
    ADD_FAILURE() << folder << ": no " << method;
    return std::map<std::string, std::string>{};
  };
  EXPECT_EQ(row("dq", "penalty").at("rhs_evals"), row("dq", "penalty-dq").at("rhs_evals"));
  EXPECT_EQ(row("dq", "penalty").at("steps"), row("dq", "penalty-dq").at("steps"));
  // Difference quotients cost a right-hand side per state component and Jacobian.
  EXPECT_GT(std::stol(row("dq", "penalty").at("rhs_evals")),
            std::stol(row("analytic", "penalty").at("rhs_evals")));
}

// KLU takes only the analytic Jacobian. 'all' with it ran penalty, then stopped at penalty-dq with
// exit 2 and wrote nothing: it leaves penalty-dq out now; asked for by name, it is still refused.
TEST_F(BallDropCli, AllWithKluLeavesOutTheDifferenceQuotientMethod) {
  const Outcome all = run("--linear-solver klu --t-end 0.6 --out klu");
  ASSERT_EQ(all.code, 0) << all.err;
  const std::string csv = slurp(dir_ / "klu" / "comparison.csv");
  EXPECT_NE(csv.find("\npenalty,success"), std::string::npos) << csv;
  EXPECT_EQ(csv.find("\npenalty-dq,"), std::string::npos) << csv;
  const Outcome named = run("--method penalty-dq --linear-solver klu --out named");
  EXPECT_EQ(named.code, 2);
  EXPECT_NE(named.err.find("--linear-solver: value 'klu' needs the analytic Jacobian"), std::string::npos)
      << named.err;
}
