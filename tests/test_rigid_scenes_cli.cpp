// The rigid_scenes experiment: the scenes' physics as a reader checks it, by every method, and the
// command-line contract.
#include "cli_fixture.hpp"

#include <cmath>
#include <map>

namespace {

class RigidScenesCli : public CliTest {};

// scene,method,quantity -> value, from observables.csv.
std::map<std::string, double> observables(const std::string& csv) {
  std::map<std::string, double> out;
  const auto rows = csv_rows(csv);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& c = rows[i];
    out[c[0] + "," + c[1] + "," + c[2]] = c[3] == "nan" ? std::nan("") : std::stod(c[3]);
  }
  return out;
}

}  // namespace

// The off-centre hit, in closed form: the ball (m = 0.17 kg, e = 1, 2 m/s) strikes the box's +x
// face (M = 1 kg, half extents 0.3, 0.2, 0.1 m) 0.6 * 0.2 = 0.12 m off its centre line. The impulse
// along the normal is J = (1 + e) v / (1/m + 1/M + r^2 / I_zz), with r = 0.12 m and
// I_zz = M (0.3^2 + 0.2^2) / 3; the box leaves at J / M and spins at J r / I_zz.
double off_centre_impulse() {
  const double m = 0.17, M = 1.0, v = 2.0, e = 1.0, r = 0.6 * 0.2, I = M * (0.3 * 0.3 + 0.2 * 0.2) / 3;
  return (1 + e) * v / (1 / m + 1 / M + r * r / I);
}
double off_centre_spin() { return off_centre_impulse() * 0.6 * 0.2 / (1.0 * (0.3 * 0.3 + 0.2 * 0.2) / 3); }

// Expected values, derived:
// - snooker, e = 1, equal masses: exchange (penalty: exact for a linear spring between equal
//   masses, to the solver's tolerance).
// - planet: momentum gives it at most 2 (m/M) v = 4e-6 m/s; the cue ball returns at -2 m/s.
// - spinning box: the ball leaves with the same speed by every impulsive/penalty method.
// - rubber-steel: first apex / release height = e^2 = 0.81 and 0.16 (event-driven: exact flight
//   between exact impulses; game and penalty within their O(dt) and O(g/(wV)) errors, 1e-2).
// - cradle by impulses: the last ball leaves at the striker's 1 m/s.
// - projection alone: the cue ball keeps pushing, the red ball is displaced, nothing bounces.
TEST_F(RigidScenesCli, ScenesBehaveAsPhysicsSays) {
  const Outcome r = run(RIGID_SCENES_EXE, "--out scenes");
  ASSERT_EQ(r.code, 0) << r.err;
  auto o = observables(slurp(dir_ / "scenes" / "observables.csv"));
  for (const char* m : {"penalty", "game-symplectic", "event-ode"}) {
    const std::string M = m;
    EXPECT_NEAR(o["snooker," + M + ",cue_vx_mps"], 0.0, 1e-5) << m;
    EXPECT_NEAR(o["snooker," + M + ",red_vx_mps"], 2.0, 1e-5) << m;
    EXPECT_LE(o["planet," + M + ",planet_speed_mps"], 4e-6 * (1 + 1e-6)) << m;
    EXPECT_NEAR(o["planet," + M + ",cue_vx_mps"], -2.0, 1e-5) << m;
    EXPECT_NEAR(o["spinning-box," + M + ",ball_speed_mps"], o["spinning-box,event-ode,ball_speed_mps"], 1e-2)
        << m;
    // Off-centre (closed form below): event and game apply the exact impulse; the penalty
    // spring's contact lasts ~1 ms while the box turns, which moves the lever arm by ~1e-3.
    const double tol = M == "penalty" ? 1e-2 : 1e-9;
    EXPECT_NEAR(o["off-centre," + M + ",box_spin_radps"] / off_centre_spin(), 1.0, tol) << m;
    EXPECT_NEAR(o["off-centre," + M + ",box_speed_mps"] / off_centre_impulse(), 1.0, tol) << m;
    EXPECT_NEAR(o["rubber-steel," + M + ",rubber_apex_ratio"], 0.81, 1e-2) << m;
    EXPECT_NEAR(o["rubber-steel," + M + ",steel_apex_ratio"], 0.16, 1e-2) << m;
  }
  EXPECT_GT(o["spinning-box,event-ode,ball_speed_mps"], 0.5) << "spin alone knocks the ball away";
  EXPECT_NEAR(o["rubber-steel,event-ode,rubber_apex_ratio"], 0.81, 1e-6);
  EXPECT_NEAR(o["cradle,event-ode,last_vx_mps"], 1.0, 1e-12);
  EXPECT_NEAR(o["cradle,game-symplectic,last_vx_mps"], 1.0, 1e-12);
  EXPECT_NEAR(o["snooker,game-symplectic-projection,cue_vx_mps"], 2.0, 1e-12)
      << "projection never changes velocity";
  // The cue ball pushes the red ball along: each step's overlap 2 dt is split by inverse mass,
  // so the red ball advances at half the cue's 2 m/s from contact (after the 1 mm gap, 0.5 ms)
  // to the end (0.05 s): 0.0495 m, to within a step's advance.
  EXPECT_NEAR(o["snooker,game-symplectic-projection,red_displacement_m"], 0.5 * 2.0 * (0.05 - 0.0005),
              2.0 * 1e-4);
  EXPECT_NEAR(o["snooker,game-symplectic-projection,contact_duration_s"], 0.05 - 0.0005, 2e-4)
      << "it pushes to the end";
  // The sequential rule's order-dependence, measured: two simultaneous contacts. Penalty springs
  // act together and keep the symmetry; sequential impulses break it, and resolving in the other
  // order mirrors the outcome exactly.
  EXPECT_NEAR(o["wedge,penalty,upper_speed_mps"], o["wedge,penalty,lower_speed_mps"], 1e-6);
  EXPECT_NEAR(o["wedge,penalty,striker_vy_mps"], 0.0, 1e-6);
  EXPECT_GT(o["wedge,event-ode,upper_speed_mps"] - o["wedge,event-ode,lower_speed_mps"], 0.1);
  EXPECT_NEAR(o["wedge,event-ode,upper_speed_mps"], o["wedge,event-ode-reversed,lower_speed_mps"], 1e-12);
  EXPECT_NEAR(o["wedge,event-ode,striker_vy_mps"], -o["wedge,event-ode-reversed,striker_vy_mps"], 1e-12);
}

// The same hit with the box turned any way (and given as an unnormalised quaternion of huge
// entries, whose plain norm overflows): the spin's magnitude is frame-independent.
TEST_F(RigidScenesCli, OffCentreSpinIsTheSameInEveryOrientation) {
  for (const char* q : {"0.9 0.1 0.3 0.2", "1e200 1e200 1e200 1e200"}) {
    const Outcome r =
        run(RIGID_SCENES_EXE,
            std::string("--scene off-centre --method event-ode --quaternion ") + q + " --out s");
    ASSERT_EQ(r.code, 0) << q << ": " << r.err;
    auto o = observables(slurp(dir_ / "s" / "observables.csv"));
    EXPECT_NEAR(o["off-centre,event-ode,box_spin_radps"] / off_centre_spin(), 1.0, 1e-9) << q;
  }
}

TEST_F(RigidScenesCli, BadInputIsRefused) {
  expect_refused(
      RIGID_SCENES_EXE,
      {
          {"--m 0", "--m", "'0'", "(0, inf)"},
          // Refused before any run, by the run that needs the longest
          // step: 0.05 s / 1e8 of 10 sweeps a step, rounded up.
          {"--scene snooker --dt 1e-12", "--dt", "'1e-12'", "sequential-impulses on snooker over 0.05 s"},
          {"--scene snooker --dt 1e-12", "--dt", "'1e-12'", "accepted --dt >= 5.01e-09"},
          {"--m -1", "--m", "'-1'", "(0, inf)"},
          {"--radius 0", "--radius", "'0'", "(0, inf)"},
          // Accepted alone, beyond a body's doubles in its inertia: it was
          // refused as 'cue inverse inertia', no option named.
          {"--radius 1e-300", "--radius", "'1e-300'", "finite and positive"},
          {"--half-extents 0.1 0 0.1", "--half-extents", "'0'", "(0, inf)"},
          {"--elasticity -0.5", "--elasticity", "'-0.5'", "[0, 1]"},
          // A restitution (the product of the pair's) above one.
          {"--elasticity 40", "--elasticity", "'40'", "[0, 1]"},
          {"--quaternion 0 0 0 0", "--quaternion", "'0 0 0 0'", "non-zero"},
          {"--quaternion 1 nan 0 0", "--quaternion", "'nan'", "(-inf, inf)"},
          {"--scene pool", "--scene", "'pool'", "snooker"},
      });
}
