#include "contact_ode/models/ball_stack.hpp"

#include "contact_ode/models/law_registry.hpp"
#include "contact_ode/models/scene_registry.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace contact {

BallStack::BallStack(BallStackParams p) : OneLawSystem(p.law), p_(std::move(p)) {
  if (p_.n < 1) throw std::invalid_argument("ball stack: n = 0 balls; accepted range [1, inf)");
}

Mask BallStack::position_mask() const { return interleaved_positions(p_.n); }

Vector BallStack::initial_state() const {
  Vector y = Vector::Zero(static_cast<Eigen::Index>(2 * p_.n));
  for (std::size_t b = 0; b < p_.n; ++b) y[static_cast<Eigen::Index>(2 * b)] = p_.drop;
  return y;
}

std::vector<std::string> BallStack::state_labels() const { return interleaved_labels(p_.n); }

// Contact i pushes ball i up and ball i-1 (if any) down. A resting contact i (event-driven rest)
// holds ball i still, which is the column's motion when every contact below it rests too.
void BallStack::rhs(double, ConstVectorRef y, const ContactModes& modes, VectorRef ydot) const {
  for (std::size_t b = 0; b < p_.n; ++b) {
    ydot[static_cast<Eigen::Index>(2 * b)] = v(y, b);
    ydot[static_cast<Eigen::Index>(2 * b + 1)] = -p_.g;
  }
  for (std::size_t i = 0; i < p_.n; ++i) {
    if (modes[i] != ContactMode::Penalty) continue;
    const double F = force(p_.law, -gap(i, y), -gap_rate(i, y)) / p_.m;
    ydot[static_cast<Eigen::Index>(2 * i + 1)] += F;
    if (i > 0) ydot[static_cast<Eigen::Index>(2 * i - 1)] -= F;
  }
  for (std::size_t b = 0; b < p_.n; ++b)
    if (modes[b] == ContactMode::Resting)
      ydot[static_cast<Eigen::Index>(2 * b)] = ydot[static_cast<Eigen::Index>(2 * b + 1)] = 0.0;
}

void BallStack::jacobian(double, ConstVectorRef y, const ContactModes& modes, SparseMatrix& J) const {
  // With delta_i = -(u_i - u_{i-1}): dF_i/du_i = -F_d, dF_i/du_{i-1} = +F_d (the same for rates),
  // into v_i' with + and into v_{i-1}' with -. Every entry of the pattern is stored.
  std::vector<Triplet> t;
  t.reserve(10 * p_.n);
  // A resting ball's rows are zero, as in rhs(); their entries stay in the pattern.
  auto add = [&](int row, int col, double value) {
    t.emplace_back(row, col, modes[static_cast<std::size_t>(row / 2)] == ContactMode::Resting ? 0.0 : value);
  };
  for (std::size_t b = 0; b < p_.n; ++b) {
    const int x = static_cast<int>(2 * b);
    add(x, x, 0.0);
    add(x, x + 1, 1.0);
    add(x + 1, x + 1, 0.0);
  }
  for (std::size_t i = 0; i < p_.n; ++i) {
    double Fd = 0, Fr = 0;
    if (modes[i] == ContactMode::Penalty) {
      Fd = dforce_ddelta(p_.law, -gap(i, y), -gap_rate(i, y)) / p_.m;
      Fr = dforce_drate(p_.law, -gap(i, y), -gap_rate(i, y)) / p_.m;
    }
    const int xi = static_cast<int>(2 * i), vi = xi + 1;
    add(vi, xi, -Fd);
    add(vi, vi, -Fr);
    if (i == 0) continue;
    const int xl = xi - 2, vl = xi - 1;
    add(vi, xl, Fd);
    add(vi, vl, Fr);
    add(vl, xi, Fd);
    add(vl, vi, Fr);
    add(vl, xl, -Fd);
    add(vl, vl, -Fr);
  }
  J.resize(static_cast<Eigen::Index>(2 * p_.n), static_cast<Eigen::Index>(2 * p_.n));
  J.setFromTriplets(t.begin(), t.end());  // duplicates (a ball in two contacts) are summed
}

double BallStack::energy(ConstVectorRef y) const {
  return energy_without_springs(y) + engaged_elastic_energy(y);
}

double BallStack::energy_without_springs(ConstVectorRef y) const {
  double E = 0;
  for (std::size_t b = 0; b < p_.n; ++b)
    E += 0.5 * p_.m * v(y, b) * v(y, b) +
         p_.m * p_.g * ((2.0 * static_cast<double>(b) + 1) * p_.radius + u(y, b));
  return E;
}

void BallStack::push_apart(std::size_t i, double amount, int offset, VectorRef y) const {
  y[static_cast<Eigen::Index>(2 * i) + offset] += amount;
  if (i > 0) y[static_cast<Eigen::Index>(2 * i - 2) + offset] -= amount;
}

void BallStack::project(std::size_t i, VectorRef y) const {
  // By inverse-mass share: the ball above takes all of a floor overlap, half of a pair's.
  const double overlap = -gap(i, y);
  if (overlap > 0) push_apart(i, i ? 0.5 * overlap : overlap, 0, y);
}

double BallStack::apply_impulse(std::size_t i, double e, VectorRef y) const {
  const double J = -(1.0 + e) * gap_rate(i, y) / inverse_mass(i, y);
  apply_normal_impulse(i, J, y);
  return J;
}

void BallStack::settle(std::size_t i, VectorRef y) const {
  project(i, y);
  apply_impulse(i, 0.0, y);  // no relative normal motion left
}

void BallStack::apply_normal_impulse(std::size_t i, double lambda, VectorRef y) const {
  push_apart(i, lambda / p_.m, 1, y);
}

void BallStack::apply_normal_displacement(std::size_t i, double dlambda, VectorRef y) const {
  push_apart(i, dlambda / p_.m, 0, y);
}

namespace {
// How many balls a scene takes.
constexpr Range kBallCount{.lo = 1, .hi = 1e7, .lo_open = false, .whole = true};
}  // namespace

SceneEntry ball_stack_scene() {
  const BallStackParams d;
  return {"ball-stack",
          "a column of equal balls resting on the floor under gravity (resting contact)",
          {{"n", "", static_cast<double>(d.n), "number of balls", kBallCount},
           {"m", "kg", d.m, "mass of each ball", kPositive},
           {"radius", "m", d.radius, "radius of each ball", kPositive},
           {"g", "m/s^2", d.g, "gravity", kNonNegative},
           {"drop", "m", d.drop, "height the column is released from", kNonNegative},
           {"e", "", d.e, "restitution (impulses; the damped laws are tuned to it)", kUnitInterval},
           {"k", "N/m", 1e5, "contact stiffness", kPositive}},
          "hooke",
          {"sink of the top ball", "penetration", "jitter", "energy", "cost per simulated second"},
          "penalty at rest: contact b squeezed by (n - b) m g / k, the top sunk by m g n (n + 1) / (2 k)",
          2.0,
          [](const ParameterValues& v, const std::string& law) -> std::unique_ptr<Dynamics> {
            const double n = v.at("n");  // a whole number in its range (kBallCount)
            const double V = std::sqrt(2 * v.at("g") * v.at("drop"));
            const LawSpec spec{.k = v.at("k"), .m = v.at("m"), .e = v.at("e"), .v = V > 0 ? V : 1.0};
            return std::make_unique<BallStack>(BallStackParams{.n = static_cast<std::size_t>(n),
                                                               .m = v.at("m"),
                                                               .radius = v.at("radius"),
                                                               .g = v.at("g"),
                                                               .drop = v.at("drop"),
                                                               .e = v.at("e"),
                                                               .law = make_law(law, spec)});
          }};
}

SphereLineLayout BallStack::sphere_line() const {
  SphereLineLayout l{
      .radius = p_.radius, .vertical = true, .g = p_.g, .floor = true, .mass = {}, .rest_centre = {}};
  for (std::size_t b = 0; b < p_.n; ++b) {
    l.mass.push_back(p_.m);
    l.rest_centre.push_back(static_cast<double>(2 * b + 1) * p_.radius);
  }
  return l;
}

}  // namespace contact
