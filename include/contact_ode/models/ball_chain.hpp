#pragma once
// N-ball chain (Newton's cradle generalised): N equal balls of mass m [kg] on a line, no
// gravity. Only the gaps between them enter the dynamics, so the balls' size does not appear. Ball 0, the
// striker, starts a distance `approach` [m] from ball 1 moving at v0 [m/s] towards it; balls 1..N-1 rest with
// `spacing` [m] between neighbours (0: touching). Positions are displacements u_b from the rest positions
// (balls `spacing` apart), so that
//   gap_i = spacing + u_{i+1} - u_i
// is exactly zero for touching balls: with absolute positions, rounding in x_{i+1} - x_i - 2r
// left "touching" gaps of +-1e-17 m (1e-13 m a thousand metres down a long chain), each a
// spurious contact switch and a restart of the integrator.
// Contact i joins balls i and i+1:
//   gap       spacing + u_{i+1} - u_i,   overlap delta = -gap,   delta_dot = v_i - v_{i+1}
//   penalty   F = law(delta, delta_dot) pushes ball i back and ball i+1 on
//   impulse   J = -(1+e) (v_{i+1} - v_i) / (1/m + 1/m) along the line
//   energy    sum m v^2 / 2 + stored spring energy
// State interleaved as y = [u0, v0, u1, v1, ...], so the Jacobian is banded (3 below the diagonal,
// 2 above): band and sparse solvers scale linearly in N.
#include "contact_ode/models/contact_law.hpp"
#include "contact_ode/models/mechanical_system.hpp"
#include "contact_ode/models/neighbour_dynamics.hpp"

namespace contact {

struct BallChainParams {
  std::size_t n = 5;       // number of balls (>= 2)
  double m = 0.1;          // mass of each ball [kg]
  double v0 = 1.0;         // striker velocity [m/s]
  double approach = 0.01;  // striker's initial distance to ball 1 [m]
  double spacing = 0.0;    // gap between the resting balls [m]
  double e = 1.0;          // Newton restitution for impulses
  ContactLaw law = Hooke{1e6};
};

class BallChain final : public OneLawSystem,
                        public NormalImpulses,
                        public NeighbourDynamics,
                        public SphereLine {
 public:
  explicit BallChain(BallChainParams p);
  const BallChainParams& params() const { return p_; }

  std::string name() const override { return "ball-chain"; }
  Mask position_mask() const override;
  std::size_t state_size() const override { return 2 * p_.n; }
  Vector initial_state() const override;
  std::vector<std::string> state_labels() const override;

  void rhs(double t, ConstVectorRef y, const ContactModes& modes, VectorRef ydot) const override;
  void jacobian(double t, ConstVectorRef y, const ContactModes& modes, SparseMatrix& J) const override;
  // With y = [u0, v0, u1, v1, ...]: v_i' depends on u_{i-1} (3 columns left of it) through
  // v_{i+1} (2 columns right).
  Bandwidth jacobian_bandwidth() const override { return {3, 2}; }
  double energy(ConstVectorRef y) const override;
  double energy_without_springs(ConstVectorRef y) const override;
  double mean_mass() const override { return p_.m; }

  std::size_t contact_count() const override { return p_.n - 1; }
  double gap(std::size_t i, ConstVectorRef y) const override { return p_.spacing + (u(y, i + 1) - u(y, i)); }
  double gap_rate(std::size_t i, ConstVectorRef y) const override { return v(y, i + 1) - v(y, i); }
  void gaps_and_rates(ConstVectorRef y, std::span<double> d, std::span<double> r) const override {
    direct_gaps_and_rates(*this, y, d, r);
  }
  double restitution(std::size_t) const override { return p_.e; }
  void project(std::size_t i, VectorRef y) const override;
  double apply_impulse(std::size_t i, double e, VectorRef y) const override;
  void settle(std::size_t i, VectorRef y) const override;
  bool holds_at_rest(std::size_t) const override { return false; }  // two moving balls (settle)

  // Ball i and i+1 take -lambda/m and +lambda/m: w = 2/m.
  double inverse_mass(std::size_t, ConstVectorRef) const override { return 2.0 / p_.m; }
  void apply_normal_impulse(std::size_t i, double lambda, VectorRef y) const override;
  void apply_normal_displacement(std::size_t i, double dlambda, VectorRef y) const override;
  // Spheres of radius 0.025 m (the dynamics never see it) on a horizontal line, no floor.
  SphereLineLayout sphere_line() const override;
  LinearLaw linear_law(std::size_t) const override { return contact::linear_law(p_.law); }

  std::size_t bodies() const override { return p_.n; }
  std::size_t body_stride() const override { return 2; }
  void range_rhs(double t, std::size_t first, std::size_t count, ConstVectorRef window,
                 VectorRef ydot) const override;

 private:
  static double u(ConstVectorRef y, std::size_t b) { return y[static_cast<Eigen::Index>(2 * b)]; }
  static double v(ConstVectorRef y, std::size_t b) { return y[static_cast<Eigen::Index>(2 * b + 1)]; }
  BallChainParams p_;
};

}  // namespace contact
