#include "contact_ode/models/ball_drop.hpp"

#include "contact_ode/models/law_registry.hpp"
#include "contact_ode/models/scene_registry.hpp"

#include <cmath>
#include <limits>

namespace contact {

namespace {
constexpr double kFloorInverseMass = 0.0;  // the floor is static: infinite mass
}

void BallDrop::rhs(double, ConstVectorRef y, const ContactModes& modes, VectorRef ydot) const {
  switch (modes[0]) {
    case ContactMode::Free:
      ydot << y[1], -p_.g;
      break;
    case ContactMode::Penalty:
      ydot << y[1], -p_.g + force(p_.law, -y[0], -y[1]) / p_.m;
      break;
    case ContactMode::Resting:
      ydot << 0.0, 0.0;
      break;
  }
}

void BallDrop::jacobian(double, ConstVectorRef y, const ContactModes& modes, SparseMatrix& J) const {
  // Pattern [0 1; a b] with the diagonal, entries zero where the mode has none.
  double dx = 1.0, a = 0.0, b = 0.0;
  if (modes[0] == ContactMode::Resting) dx = 0.0;
  if (modes[0] == ContactMode::Penalty) {
    // v' = -g + F(-x, -v)/m, so dv'/dx = -F_delta/m and dv'/dv = -F_rate/m.
    a = -dforce_ddelta(p_.law, -y[0], -y[1]) / p_.m;
    b = -dforce_drate(p_.law, -y[0], -y[1]) / p_.m;
  }
  const Triplet entries[] = {{0, 0, 0.0}, {0, 1, dx}, {1, 0, a}, {1, 1, b}};
  J.resize(2, 2);
  J.setFromTriplets(std::begin(entries), std::end(entries));
}

double BallDrop::energy(ConstVectorRef y) const {
  // In flight (x >= 0) no law is engaged: the common case skips the law's dispatch.
  const double mechanical = energy_without_springs(y);
  return y[0] >= 0 ? mechanical : mechanical + engaged_elastic_energy(y);
}

double BallDrop::energy_without_springs(ConstVectorRef y) const {
  return 0.5 * p_.m * y[1] * y[1] + p_.m * p_.g * y[0];
}

void BallDrop::project(std::size_t, VectorRef y) const {
  const double penetration = -y[0];
  if (penetration <= 0) return;
  const double inv_m = 1.0 / p_.m;
  y[0] += penetration * inv_m / (inv_m + kFloorInverseMass);
}

double BallDrop::apply_impulse(std::size_t, double e, VectorRef y) const {
  // Normal n = +1 from floor to ball; relative normal velocity v_r.n = v - 0.
  const double inv_m = 1.0 / p_.m;
  const double J = -(1.0 + e) * y[1] / (inv_m + kFloorInverseMass);
  y[1] += J * inv_m;
  return J;
}

void BallDrop::propagate(ConstVectorRef y0, double dt, VectorRef y) const {
  y << y0[0] + dt * (y0[1] - 0.5 * p_.g * dt), y0[1] - p_.g * dt;
}

double BallDrop::time_to_impact(std::size_t, ConstVectorRef y0) const {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double x = y0[0], v = y0[1], g = p_.g;
  if (g == 0.0) return v < 0 && x >= 0 ? -x / v : inf;
  // Larger root of x + v t - g t^2/2 = 0, written without cancellation for either sign of v. s is
  // sqrt(v^2 + 2 g x), the speed at the floor: impact_speed above it; below it (an overlap of
  // rounding's size) from square roots where v^2 + 2 g x is subnormal, zero or past the doubles.
  double s = 0;
  if (x >= 0) {
    s = impact_speed(x, v, g);
  } else if (const double disc = v * v + 2.0 * g * x;
             std::abs(disc) >= 0x1p-800 && std::abs(disc) <= 0x1p800) {
    if (disc < 0) return inf;
    s = std::sqrt(disc);
  } else {
    const double w = std::sqrt(2.0) * std::sqrt(g) * std::sqrt(-x), u = std::abs(v);
    if (u < w) return inf;
    s = std::sqrt(u - w) * std::sqrt(u + w);
  }
  return v >= 0 ? (v + s) / g : 2.0 * x / (s - v);
}

double impact_speed(double h0, double v0, double g) {
  // Where the square is subnormal, zero or past the doubles (a drop of 1e-165 m, or of 1e157 m, under
  // gravity scaled alike), from square roots instead: its terms are never formed.
  const double square = v0 * v0 + 2.0 * g * h0;
  if (square >= 0x1p-800 && square <= 0x1p800) return std::sqrt(square);
  return std::hypot(v0, std::sqrt(2.0) * std::sqrt(g) * std::sqrt(h0));
}

double BallDrop::time_to_apex(std::size_t, ConstVectorRef y0) const {
  return (y0[1] > 0 && p_.g > 0) ? y0[1] / p_.g : std::numeric_limits<double>::infinity();
}

}  // namespace contact

namespace contact {

SceneEntry ball_drop_scene() {
  const BallDropParams d;
  return {"ball-drop",
          "a point mass dropped on a rigid floor",
          {{"m", "kg", d.m, "mass", kPositive},
           {"g", "m/s^2", d.g, "gravity", kNonNegative},
           {"h0", "m", d.h0, "initial height", kNonNegative},
           {"v0", "m/s", d.v0, "initial vertical velocity"},
           {"e", "", d.e, "restitution (impulses; the damped laws are tuned to it)", kUnitInterval},
           {"k", "N/m", 1e5, "contact stiffness", kPositive}},
          "hooke",  // the tutorial's undamped spring: e reaches the impulses and the damped laws only
          {"bounce times", "apex heights", "contact duration", "penetration", "restitution", "energy"},
          "event-driven: apexes e^(2n) h0, Zeno time; penalty: hooke_contact with gravity",
          3.0,
          [](const ParameterValues& v, const std::string& law) -> std::unique_ptr<Dynamics> {
            const double V = impact_speed(v.at("h0"), v.at("v0"), v.at("g"));
            const LawSpec spec{.k = v.at("k"), .m = v.at("m"), .e = v.at("e"), .v = V > 0 ? V : 1.0};
            return std::make_unique<BallDrop>(
                BallDropParams{v.at("m"), v.at("g"), v.at("h0"), v.at("v0"), v.at("e"), make_law(law, spec)});
          }};
}

SphereLineLayout BallDrop::sphere_line() const {
  constexpr double r = 0.1;
  return {.radius = r, .vertical = true, .g = p_.g, .floor = true, .mass = {p_.m}, .rest_centre = {r}};
}

}  // namespace contact
