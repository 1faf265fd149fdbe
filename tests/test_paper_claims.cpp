// Each claim the paper's abstract makes (and the comparisons its text draws from CPU times), read
// from the full study's results that the paper_builds test leaves in PAPER_RESULTS and compared, so
// that a regression in the data fails the claim. Run after paper_builds (a CTest fixture).
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/analysis/table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Where = std::vector<std::pair<std::string, std::string>>;

bool same(const std::string& cell, const std::string& wanted) {
  if (cell == wanted) return true;
  char* end = nullptr;
  const double x = std::strtod(cell.c_str(), &end);
  return *end == '\0' && !cell.empty() && std::abs(x - std::stod(wanted)) <= 1e-12 * std::abs(x);
}

// The number in `column` of the first row of `file` (under the results) matching every pair.
double cell(const std::string& file, const Where& where, const std::string& column) {
  for (const auto& row : contact::read_csv(fs::path(PAPER_RESULTS) / file)) {
    bool all = true;
    for (const auto& [key, value] : where) all = all && row.count(key) && same(row.at(key), value);
    if (all) return std::stod(row.at(column));
  }
  ADD_FAILURE() << file << ": no row for the claim";
  return std::nan("");
}

}  // namespace

// "The penalty contact lasts pi sqrt(m/k) and penetrates V sqrt(m/k)", and Section 4.1's (and the
// README's) "the fitted exponents are within 0.002 of -1/2 for every law": gravity's share g / (w V)
// shifts them (0.0011 measured for each law).
TEST(PaperClaims, PenetrationAndDurationScaleAsKToTheMinusHalf) {
  for (const char* law : {"hooke", "kelvin-voigt", "kelvin-voigt-clamped"})
    for (const char* column : {"penetration_exponent", "duration_exponent"})
      EXPECT_NEAR(cell("k_sweep/exponents.csv", {{"law", law}}, column), -0.5, 0.002) << law << " " << column;
}

// Section 4.1: "beside the closed forms, gravity included, which every measured contact matches to
// 1e-7 for every law and every k". k_sweep solves at rtol 1e-10: ~300 steps per contact at that
// local error leave ~3e-8 (measured: 3.4e-8, Hooke's duration at k = 1e9). The Kelvin–Voigt
// references were the gravity-free limit, 1e-3 ... 0.5 off at k <= 1e4.
TEST(PaperClaims, EveryMeasuredContactMatchesItsExactClosedForm) {
  int rows = 0;
  for (const auto& row : contact::read_csv(fs::path(PAPER_RESULTS) / "k_sweep" / "k_sweep.csv")) {
    if (row.at("first_bounce") != "bounced") continue;
    ++rows;
    for (const char* what : {"penetration_m", "duration_s"})
      EXPECT_NEAR(std::stod(row.at(what)) / std::stod(row.at(std::string("closed_form_") + what)), 1.0, 1e-7)
          << row.at("law") << " k = " << row.at("k_N_per_m") << " " << what;
  }
  EXPECT_GE(rows, 3 * 17);  // three laws, k = 1e2 ... 1e10 at two points per decade at least
}

// "The cost per contact of every adaptive code, explicit or implicit, is flat in k" (a code whose step
// were bound by stability in the contact would show k^(1/2)). The CPU times the text quotes beside it
// are measurements, not claims a test could time: speed belongs in the benchmarks.
TEST(PaperClaims, AResolvedContactIsNotStiff) {
  for (const char* name : {"cvode-bdf", "cvode-adams", "arkode-erk", "gsl-rkf45", "gsl-rk8pd", "arkode-dirk"})
    EXPECT_LT(std::abs(cell("contact_cost/exponents.csv", {{"integrator", name}}, "rhs_exponent")), 0.05)
        << name;
}

// "A contact at rest is stiff, and there only the implicit codes' cost stays flat": on the
// resting column the implicit codes' evaluations per simulated second follow k^0 (they pay for the
// ring-down, whose length in periods the damping ratio fixes; measured -0.11 to -0.05) and the explicit
// method's grow toward its stability bound's k^(1/2) (0.43 over 1e5 ... 1e8; test_resting_cost_cli
// derives both).
TEST(PaperClaims, AContactAtRestIsStiff) {
  for (const char* name : {"cvode-bdf", "cvode-adams", "arkode-dirk"})
    EXPECT_LT(std::abs(cell("resting_cost/exponents.csv", {{"integrator", name}}, "rhs_exponent")), 0.15)
        << name;
  EXPECT_GT(cell("resting_cost/exponents.csv", {{"integrator", "arkode-erk"}}, "rhs_exponent"), 0.3);
}

// "Scored against the rigid body, the penalty ball keeps an error of 0.211 at k = 1e4 however tight
// the tolerance, while event-driven impulses reach 1e-9": the floor is the spring model's own error,
// the closed forms' difference (to 1e-5, CVODE's error at rtol 1e-9 being ~1e-7).
TEST(PaperClaims, AgainstTheRigidBodyThePenaltyKeepsItsModellingError) {
  const auto spring = contact::hooke_ball_state(1, 1e4, 1, 0, 9.81, 1.5);
  const auto rigid = contact::rigid_ball_state(1, 0, 9.81, 1, 1.5);
  const double modelling =
      std::max(std::abs(spring.x - rigid.x), std::abs(spring.v - rigid.v) / std::sqrt(2 * 9.81));
  const auto physical = [](const char* paradigm, const char* value) {
    return cell("work_precision/work_precision.csv",
                {{"problem", "ball"}, {"paradigm", paradigm}, {"integrator", "cvode-bdf"}, {"value", value}},
                "error_physical");
  };
  EXPECT_NEAR(physical("penalty", "1e-9"), modelling, 1e-5);
  EXPECT_NEAR(physical("penalty", "1e-6"), modelling, 1e-3);
  EXPECT_LT(physical("event", "1e-9"), 1e-7);
}

// Section 4.5: "the exact integrator sits at the floor the others approach": its error against the
// spring's closed form is rounding (1e-15 measured; 1e-13 allows for the roots' 100 ulps of t), at
// or below every other integrator's at every tolerance and step of the sweep, and only GSL's
// extrapolation method comes within a factor 100 (3e-14 ... 2e-13 measured).
TEST(PaperClaims, TheExactIntegratorIsTheFloorOfTheWorkPrecisionSweep) {
  const double exact =
      cell("work_precision/work_precision.csv",
           {{"problem", "ball"}, {"paradigm", "penalty"}, {"integrator", "exact-linear"}}, "error_model");
  EXPECT_LT(exact, 1e-13);
  int others = 0, extrapolations = 0;
  for (const auto& row : contact::read_csv(fs::path(PAPER_RESULTS) / "work_precision/work_precision.csv"))
    if (row.at("problem") == "ball" && row.at("paradigm") == "penalty" &&
        row.at("integrator") != "exact-linear") {
      ++others;
      const double error = std::stod(row.at("error_model"));
      EXPECT_GE(error, exact) << row.at("integrator") << " " << row.at("value");
      if (row.at("integrator") != "gsl-bsimp") {
        EXPECT_GT(error, 100 * exact) << row.at("integrator") << " " << row.at("value");
      } else {  // "near rounding at every tolerance": 1e-12, a few thousand ulps of a state of order one
        EXPECT_LT(error, 1e-12) << "gsl-bsimp " << row.at("value");
        ++extrapolations;
      }
    }
  EXPECT_GT(others, 50);
  EXPECT_EQ(extrapolations, 7);  // rtol 1e-3 ... 1e-9
}

// "Explicit Euler invents energy": its ball drift rate at 1 ms is positive, g dt / (2 h0) per second
// of flight to first order (4.9e-3) plus what its contacts add.
TEST(PaperClaims, ExplicitEulerInventsEnergy) {
  const double rate =
      cell("energy_drift/drift.csv", {{"system", "ball"}, {"method", "game-euler"}, {"value", "1e-3"}},
           "drift_rate_per_s");
  EXPECT_GT(rate, 9.81 * 1e-3 / 2 * 0.9);
}

// "Locating the kink raises RK4 from order 2.29 to 5.97 over the asymptotic range": unlocated within
// 0.5 of the kink's 2, located at least its 4 (less 0.3).
TEST(PaperClaims, LocatingTheKinkRestoresRk4) {
  EXPECT_NEAR(cell("convergence_dt/orders.csv", {{"integrator", "rk4"}}, "fixed_order_unlocated"), 2, 0.5);
  EXPECT_GE(cell("convergence_dt/orders.csv", {{"integrator", "rk4"}}, "fixed_order_located"), 3.7);
}

// "A touching Newton's cradle of linear springs hands only 0.888 of the energy to its last ball":
// well short of the impulse answer's 1 (dispersion), and short of Hertz contacts.
TEST(PaperClaims, LinearSpringsDisperseTheCradlesPulse) {
  const double linear = cell("newton_cradle/velocities.csv",
                             {{"method", "penalty-linear"}, {"spacing_m", "0"}}, "last_ball_energy_share");
  const double hertz = cell("newton_cradle/velocities.csv", {{"method", "penalty-hertz"}, {"spacing_m", "0"}},
                            "last_ball_energy_share");
  EXPECT_LT(linear, 0.95);
  EXPECT_LT(linear, hertz);
}

// "Siconos' event-driven scheme finds the rigid apex to 6e-11 m": within 1e-8 (LSODAR at rtol 1e-10).
TEST(PaperClaims, SiconosFindsTheRigidApex) {
  EXPECT_LT(cell("engines/engines.csv", {{"scene", "drop"}, {"method", "siconos"}}, "scored_error"), 1e-8);
}

// "Event-driven impulses hold [the sixteen-ball column] exactly": the top ball's sink is zero under
// both contact orders (its contacts start at rest; they used to end the run as unresolved).
TEST(PaperClaims, EventDrivenImpulsesHoldTheRestingColumnExactly) {
  for (const char* method : {"event-ode", "event-ode-reversed"})
    EXPECT_EQ(cell("stack/stack.csv", {{"balls", "16"}, {"method", method}}, "top_sink_m"), 0.0) << method;
}

// "Without location the error of every adaptive code but one still falls with its tolerance (fitted
// exponents above one half; GSL's bsimp's only on the whole, its error at rtol 1e-4 above that at
// 1e-3) ... The exception is ARKODE's DIRK method": every other code's exponent unlocated is above
// 0.5 (0.7 to 1.1 measured; bsimp's 0.71, whose erratic errors gave 0.41 when built with FMA
// contraction), DIRK's below 0.2 (0.04 measured), and DIRK's with location above 0.8 (1.1 measured).
TEST(PaperClaims, OnlyArkodeDirkLosesItsToleranceAcrossUnlocatedKinks) {
  const std::string orders = "convergence_dt/orders.csv";
  for (const char* name : {"cvode-bdf", "cvode-adams", "arkode-erk", "arkode-imex", "gsl-rk8pd", "gsl-rkf45",
                           "gsl-msbdf", "gsl-bsimp"})
    EXPECT_GT(cell(orders, {{"integrator", name}}, "tol_exponent_unlocated"), 0.5) << name;
  const std::string adaptive = "convergence_dt/adaptive.csv";
  EXPECT_GT(
      cell(adaptive, {{"integrator", "gsl-bsimp"}, {"events", "unlocated"}, {"rtol", "1e-4"}}, "error_max"),
      cell(adaptive, {{"integrator", "gsl-bsimp"}, {"events", "unlocated"}, {"rtol", "1e-3"}}, "error_max"));
  EXPECT_LT(cell(orders, {{"integrator", "arkode-dirk"}}, "tol_exponent_unlocated"), 0.2);
  EXPECT_GT(cell(orders, {{"integrator", "arkode-dirk"}}, "tol_exponent_located"), 0.8);
}

// Section 4.3: "impulses keep the energy only as well as the flight between them is integrated".
// Impulses and rests book their losses exactly, so on rubber-steel (13 impacts, the steel ball
// bounced to rest) the event-driven ledger is off by the flights' integration error alone: about the
// tolerance per flight, within 20 rtol for its 13 flights (measured 6 rtol at 1e-6, 9 at 1e-8). A
// rested ball that kept its last, slow bounce climbed at that speed with gravity held off: 3700 rtol
// at 1e-8, from the rest and not from the flight.
TEST(PaperClaims, EventDrivenEnergyIsAsGoodAsTheFlightsTolerance) {
  for (const char* rtol : {"1e-6", "1e-8"}) {
    const double drift =
        cell("energy_drift/drift.csv", {{"system", "rubber-steel"}, {"method", "event-ode"}, {"value", rtol}},
             "max_abs_energy_error_rel");
    EXPECT_LE(drift, 20 * std::stod(rtol)) << rtol;
  }
}

// Section 4.10: "Sequential impulses lose [a share] of the touching cradle's energy, which Moreau-Jean's
// exact complementarity solve keeps". The loss is a rho^10 of ten sweeps, rho = cos^2(pi / 5) =
// 0.65 on the cradle's five balls (its law: SequentialImpulses.ATouchingRowLosesWhatItsSweepsLeave-
// Unconverged); a is not derived, so the claim is only that the loss shows (above 1 %, 2.3 %
// measured) beside Moreau-Jean's drift, rounding (1e-12 measured) below 1e-9.
TEST(PaperClaims, SequentialImpulsesLoseATouchingCradlesEnergyWhereMoreauJeanKeepsIt) {
  const std::string engines = "engines/engines.csv";
  EXPECT_GT(cell(engines, {{"scene", "cradle-0"}, {"method", "sequential-impulses"}}, "energy_drift_rel"),
            0.01);
  EXPECT_LT(cell(engines, {{"scene", "cradle-0"}, {"method", "moreau-jean"}}, "energy_drift_rel"), 1e-9);
}
