// The stability_map experiment against its analytic references.
#include "cli_fixture.hpp"

#include <cmath>
#include <map>

namespace {

class StabilityMapCli : public CliTest {};

// The game loop on the map's contact, written out: a unit mass enters a Hooke spring of stiffness
// k at speed V = 1 from half a step's travel above the floor, no gravity. A step whose start
// overlaps (x < 0) feels a = -k x; explicit Euler moves x with the old velocity, semi-implicit
// Euler with the new one. The contact ends at the first step end with x >= 0 and v >= 0, and the
// restitution is v there (the entry speed is 1). Infinity where it never ends (or blows up)
// within the experiment's time, 20 pi / w plus ten steps.
double replica(bool semi_implicit, double k, double wdt) {
  const double w = std::sqrt(k), dt = wdt / w;
  double x = 0.5 * dt, v = -1.0;
  bool in_contact = false;
  const auto steps = static_cast<long>(std::ceil((0.5 * dt + 20 * M_PI / w + 10 * dt) / dt - 1e-9));
  for (long n = 0; n < steps; ++n) {
    const double a = x < 0 ? -k * x : 0.0;
    if (semi_implicit) {
      v += dt * a;
      x += dt * v;
    } else {
      x += dt * v;
      v += dt * a;
    }
    if (!std::isfinite(x) || !std::isfinite(v)) return INFINITY;
    if (x < 0)
      in_contact = true;
    else if (in_contact && v >= 0)
      return v;
  }
  return INFINITY;
}

}  // namespace

// - Collapse: in units of 1/w (time) and V/w (length) the contact is the same for every k when
//   w dt and the entry phase (half a step) are the same, so the restitution depends on w dt only:
//   equal across k to rounding (1e-9).
// - Semi-implicit Euler below w dt = 2 keeps the energy within the modified-energy band, e^2 in
//   [(1 - x/2)/(1 + x/2), (1 + x/2)/(1 - x/2)] (test_fixed_step), and gains above it.
// - Explicit Euler multiplies the energy by 1 + x^2 > 1 every step in contact: it always gains.
TEST_F(StabilityMapCli, RestitutionFollowsTheAnalyticReferences) {
  const Outcome r = run(STABILITY_MAP_EXE, "--points 12 --out map");
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream in(slurp(dir_ / "map" / "stability.csv"));
  std::string line;
  std::getline(in, line);
  ASSERT_EQ(line, "k_N_per_m,scheme,omega_dt,dt_s,restitution,energy_ratio,reference_bound");
  std::map<std::pair<std::string, std::string>, std::vector<double>> by_wdt;  // (scheme, wdt) -> e per k
  int rows = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> c;
    std::istringstream l(line);
    for (std::string cell; std::getline(l, cell, ',');) c.push_back(cell);
    const double x = std::stod(c[2]), e = std::stod(c[4]);
    by_wdt[{c[1], c[2]}].push_back(e);
    ++rows;
    // The experiment's number is the scheme's own, to rounding: the replica repeats its
    // arithmetic, and ~1e3 steps of rounding stay below 1e-10.
    const double expected = replica(c[1] == "semi-implicit-euler", std::stod(c[0]), x);
    if (std::isinf(expected))
      EXPECT_TRUE(std::isinf(e)) << c[1] << " w dt " << x;
    else
      EXPECT_NEAR(e / expected, 1.0, 1e-10) << c[1] << " w dt " << x;
    if (c[1] == "explicit-euler") {
      EXPECT_GT(e, 1.0) << "explicit Euler gains at w dt = " << x;
    } else if (x < 2) {
      EXPECT_LE(e * e, (1 + x / 2) / (1 - x / 2) * (1 + 1e-9)) << x;
      EXPECT_GE(e * e, (1 - x / 2) / (1 + x / 2) * (1 - 1e-9)) << x;
    } else {
      EXPECT_GT(e, 1.0) << "semi-implicit Euler unstable at w dt = " << x;
    }
  }
  EXPECT_EQ(rows, 3 * 2 * 12);
  for (const auto& [key, es] : by_wdt) {
    ASSERT_EQ(es.size(), 3u);
    for (double e : es) EXPECT_NEAR(e / es.front(), 1.0, 1e-9) << key.first << " w dt " << key.second;
  }
  EXPECT_TRUE(fs::exists(dir_ / "map" / "restitution.png"));
}

TEST_F(StabilityMapCli, BadInputIsRefused) {
  expect_refused(STABILITY_MAP_EXE, {
                                        {"--points 1", "--points", "'1'", "[2, 10000]"},
                                        {"--points 1000000000", "--points", "'1000000000'", "[2, 10000]"},
                                        {"--wdt-max 0.001", "--wdt-max", "'0.001'", "(0.01, 100]"},
                                    });
}
