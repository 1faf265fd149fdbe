#include "contact_ode/models/ball_chain.hpp"

#include "contact_ode/models/law_registry.hpp"
#include "contact_ode/models/scene_registry.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace contact {

BallChain::BallChain(BallChainParams p) : OneLawSystem(p.law), p_(std::move(p)) {
  if (p_.n < 2)
    throw std::invalid_argument(fmt::format("ball chain: n = {} balls; accepted range [2, inf)", p_.n));
}

Mask BallChain::position_mask() const { return interleaved_positions(p_.n); }

Vector BallChain::initial_state() const {
  // Everything at rest at its rest position but the striker, displaced so that its gap to
  // ball 1 is `approach`: spacing + u_1 - u_0 = approach.
  Vector y = Vector::Zero(static_cast<Eigen::Index>(2 * p_.n));
  y[0] = p_.spacing - p_.approach;
  y[1] = p_.v0;
  return y;
}

std::vector<std::string> BallChain::state_labels() const { return interleaved_labels(p_.n); }

void BallChain::rhs(double, ConstVectorRef y, const ContactModes& modes, VectorRef ydot) const {
  for (std::size_t b = 0; b < p_.n; ++b) {
    ydot[static_cast<Eigen::Index>(2 * b)] = v(y, b);
    ydot[static_cast<Eigen::Index>(2 * b + 1)] = 0.0;
  }
  for (std::size_t i = 0; i + 1 < p_.n; ++i) {
    if (modes[i] != ContactMode::Penalty) continue;
    const double F = force(p_.law, -gap(i, y), -gap_rate(i, y));
    ydot[static_cast<Eigen::Index>(2 * i + 1)] -= F / p_.m;
    ydot[static_cast<Eigen::Index>(2 * i + 3)] += F / p_.m;
  }
}

void BallChain::range_rhs(double, std::size_t first, std::size_t count, ConstVectorRef window,
                          VectorRef ydot) const {
  const std::size_t w0 = first > 0 ? first - 1 : 0;  // the window's first ball
  for (std::size_t b = first; b < first + count; ++b) {
    ydot[static_cast<Eigen::Index>(2 * (b - first))] = v(window, b - w0);
    ydot[static_cast<Eigen::Index>(2 * (b - first) + 1)] = 0.0;
  }
  // Contact i joins balls i and i + 1: those touching the range are first - 1 ... first + count - 1.
  for (std::size_t i = w0; i + 1 < p_.n && i < first + count; ++i) {
    const double gap = p_.spacing + u(window, i + 1 - w0) - u(window, i - w0);
    const double rate = v(window, i + 1 - w0) - v(window, i - w0);
    if (!(contact::switching(p_.law, -gap, -rate) > 0)) continue;
    const double F = force(p_.law, -gap, -rate) / p_.m;
    if (i >= first) ydot[static_cast<Eigen::Index>(2 * (i - first) + 1)] -= F;
    if (i + 1 >= first && i + 1 < first + count)
      ydot[static_cast<Eigen::Index>(2 * (i + 1 - first) + 1)] += F;
  }
}

void BallChain::jacobian(double, ConstVectorRef y, const ContactModes& modes, SparseMatrix& J) const {
  // u_b' = v_b; contact i couples (u_i, v_i, u_{i+1}, v_{i+1}) into v_i' and v_{i+1}'. With
  // delta = u_i - u_{i+1} - spacing and delta_dot = v_i - v_{i+1}:
  //   d v_i'/d u_i = -F_d/m, d v_i'/d u_{i+1} = +F_d/m, d v_i'/d v_i = -F_r/m, d v_i'/d v_{i+1} = +F_r/m,
  // and the opposite signs for v_{i+1}'. Every entry of the pattern is stored, zero when free.
  // Written straight into compressed columns, as a GMRES run evaluates it at every Newton iteration
  // (triplets took half of such a run): ball b's columns u_b and v_b hold rows 2b - 1 (v_{b-1}'),
  // 2b (u_b': 0 and 1), 2b + 1 (v_b', from contacts b - 1 and b) and 2b + 3 (v_{b+1}'); the
  // first ball has no row 2b - 1, the last no row 2b + 3.
  const std::size_t n = p_.n;
  const auto size = static_cast<Eigen::Index>(2 * n);
  J.resize(size, size);
  J.resizeNonZeros(static_cast<Eigen::Index>(8 * n - 4));
  int* outer = J.outerIndexPtr();
  int* rows = J.innerIndexPtr();
  double* values = J.valuePtr();
  int k = 0;
  const auto put = [&](std::size_t row, double value) {
    rows[k] = static_cast<int>(row);
    values[k++] = value;
  };
  double Fd_before = 0, Fr_before = 0;  // contact b - 1's derivatives per unit mass
  for (std::size_t b = 0; b < n; ++b) {
    double Fd = 0, Fr = 0;  // contact b's
    if (b + 1 < n && modes[b] == ContactMode::Penalty) {
      Fd = dforce_ddelta(p_.law, -gap(b, y), -gap_rate(b, y)) / p_.m;
      Fr = dforce_drate(p_.law, -gap(b, y), -gap_rate(b, y)) / p_.m;
    }
    // Column u_b (u_b' does not depend on u_b: a zero stored as I - gamma J's diagonal), then
    // column v_b (u_b' = v_b). Row 2b + 1 is v_b' = (F_{b-1} - F_b) / m: both contacts' terms.
    const auto column = [&](std::size_t j, double kinematic, double before, double after) {
      outer[j] = k;
      if (b > 0) put(2 * b - 1, before);
      put(2 * b, kinematic);
      put(2 * b + 1, b == 0 ? -after : b + 1 == n ? -before : -before + -after);
      if (b + 1 < n) put(2 * b + 3, after);
    };
    column(2 * b, 0.0, Fd_before, Fd);
    column(2 * b + 1, 1.0, Fr_before, Fr);
    Fd_before = Fd;
    Fr_before = Fr;
  }
  outer[size] = k;
}

double BallChain::energy(ConstVectorRef y) const {
  return energy_without_springs(y) + engaged_elastic_energy(y);
}

double BallChain::energy_without_springs(ConstVectorRef y) const {
  double E = 0;
  for (std::size_t b = 0; b < p_.n; ++b) E += 0.5 * p_.m * v(y, b) * v(y, b);
  return E;
}

void BallChain::project(std::size_t i, VectorRef y) const {
  // Equal masses: each ball takes half the overlap (inverse-mass share).
  const double overlap = -gap(i, y);
  if (overlap <= 0) return;
  y[static_cast<Eigen::Index>(2 * i)] -= 0.5 * overlap;
  y[static_cast<Eigen::Index>(2 * i + 2)] += 0.5 * overlap;
}

double BallChain::apply_impulse(std::size_t i, double e, VectorRef y) const {
  // Normal from ball i to ball i+1; v_r.n = v_{i+1} - v_i = gap rate.
  const double inv_m = 1.0 / p_.m;
  const double J = -(1.0 + e) * gap_rate(i, y) / (inv_m + inv_m);
  y[static_cast<Eigen::Index>(2 * i + 1)] -= J * inv_m;
  y[static_cast<Eigen::Index>(2 * i + 3)] += J * inv_m;
  return J;
}

void BallChain::apply_normal_impulse(std::size_t i, double lambda, VectorRef y) const {
  y[static_cast<Eigen::Index>(2 * i + 1)] -= lambda / p_.m;
  y[static_cast<Eigen::Index>(2 * i + 3)] += lambda / p_.m;
}

void BallChain::apply_normal_displacement(std::size_t i, double dlambda, VectorRef y) const {
  y[static_cast<Eigen::Index>(2 * i)] -= dlambda / p_.m;
  y[static_cast<Eigen::Index>(2 * i + 2)] += dlambda / p_.m;
}

void BallChain::settle(std::size_t i, VectorRef y) const {
  // Both balls take their common velocity: no relative normal motion left. (Without gravity
  // nothing holds them together afterwards: the chain's dynamics treat Resting as Free.)
  project(i, y);
  const double mean = 0.5 * (v(y, i) + v(y, i + 1));
  y[static_cast<Eigen::Index>(2 * i + 1)] = y[static_cast<Eigen::Index>(2 * i + 3)] = mean;
}

}  // namespace contact

namespace contact {

namespace {
// How many balls a scene takes.
constexpr Range kBallCount{.lo = 2, .hi = 1e9, .lo_open = false, .whole = true};
}  // namespace

SceneEntry ball_chain_scene() {
  const BallChainParams d;
  return {"ball-chain",
          "Newton's cradle: a striker into a row of equal balls, no gravity",
          {{"n", "", static_cast<double>(d.n), "number of balls", kBallCount},
           {"m", "kg", d.m, "mass of each ball", kPositive},
           {"v0", "m/s", d.v0, "striker velocity"},
           {"approach", "m", d.approach, "striker's distance to ball 1", kNonNegative},
           {"spacing", "m", d.spacing, "gap between the resting balls", kNonNegative},
           {"e", "", d.e, "restitution (impulses; the damped laws are tuned to it)", kUnitInterval},
           {"k", "N/m", 1e6, "contact stiffness", kPositive}},
          "hooke",
          {"ball velocities after the impacts", "contact log", "energy"},
          "event-driven, touching balls, e = 1: the striker's velocity passes to the last ball",
          0.05,
          [](const ParameterValues& v, const std::string& law) -> std::unique_ptr<Dynamics> {
            const double n = v.at("n");  // a whole number in its range (kBallCount)
            const LawSpec spec{.k = v.at("k"), .m = v.at("m") / 2, .e = v.at("e"), .v = std::abs(v.at("v0"))};
            return std::make_unique<BallChain>(BallChainParams{static_cast<std::size_t>(n), v.at("m"),
                                                               v.at("v0"), v.at("approach"), v.at("spacing"),
                                                               v.at("e"), make_law(law, spec)});
          }};
}

SphereLineLayout BallChain::sphere_line() const {
  constexpr double r = 0.025;
  SphereLineLayout l{.radius = r, .vertical = false, .g = 0, .floor = false, .mass = {}, .rest_centre = {}};
  for (std::size_t b = 0; b < p_.n; ++b) {
    l.mass.push_back(p_.m);
    l.rest_centre.push_back(static_cast<double>(b) * (2 * r + p_.spacing));
  }
  return l;
}

}  // namespace contact
