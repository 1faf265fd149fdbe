#pragma once
// A column of n equal balls resting on the floor under gravity: the scene of resting contact,
// where every contact is closed at once and stays closed. Coordinates are each ball's height
// above its place in the touching column, u_b (centre at (2b + 1) r + u_b), so the gaps are
//   floor - ball 0:  u_0,      ball b-1 - ball b:  u_b - u_{b-1},
// and the state is interleaved (u_0, v_0, u_1, v_1, ...) for a banded Jacobian. Energy:
// kinetic + m g (centre height) + the engaged springs.
// Exact: the penalty column at rest has contact b (from the floor, b = 0) squeezed by the weight
// above it, (n - b) m g / k for a linear law, so the top sinks by m g n (n + 1) / (2 k); the
// impulsive column at rest stays where it is.
#include "contact_ode/models/contact_law.hpp"
#include "contact_ode/models/mechanical_system.hpp"

namespace contact {

struct BallStackParams {
  std::size_t n = 4;            // balls (>= 1)
  double m = 0.1;               // mass of each [kg]
  double radius = 0.05;         // [m]
  double g = 9.81;              // [m/s^2]
  double drop = 0.0;            // the whole column released this high above the floor [m]
  double e = 0.5;               // Newton restitution for impulses
  ContactLaw law = Hooke{1e5};  // every contact's penalty law
};

class BallStack final : public OneLawSystem, public NormalImpulses, public SphereLine {
 public:
  explicit BallStack(BallStackParams p);
  const BallStackParams& params() const { return p_; }

  std::string name() const override { return "ball-stack"; }
  Mask position_mask() const override;
  std::size_t state_size() const override { return 2 * p_.n; }
  Vector initial_state() const override;
  std::vector<std::string> state_labels() const override;
  std::size_t contact_count() const override { return p_.n; }
  void rhs(double t, ConstVectorRef y, const ContactModes& modes, VectorRef ydot) const override;
  void jacobian(double t, ConstVectorRef y, const ContactModes& modes, SparseMatrix& J) const override;
  Bandwidth jacobian_bandwidth() const override { return {3, 3}; }
  double energy(ConstVectorRef y) const override;
  double energy_without_springs(ConstVectorRef y) const override;
  double mean_mass() const override { return p_.m; }

  double gap(std::size_t i, ConstVectorRef y) const override { return u(y, i) - (i ? u(y, i - 1) : 0.0); }
  double gap_rate(std::size_t i, ConstVectorRef y) const override {
    return v(y, i) - (i ? v(y, i - 1) : 0.0);
  }
  void gaps_and_rates(ConstVectorRef y, std::span<double> d, std::span<double> r) const override {
    direct_gaps_and_rates(*this, y, d, r);
  }

  double restitution(std::size_t) const override { return p_.e; }
  void project(std::size_t i, VectorRef y) const override;
  double apply_impulse(std::size_t i, double e, VectorRef y) const override;
  void settle(std::size_t i, VectorRef y) const override;

  // The floor takes no share: w = 1/m for it, 2/m between two balls.
  double inverse_mass(std::size_t i, ConstVectorRef) const override { return (i ? 2.0 : 1.0) / p_.m; }
  void apply_normal_impulse(std::size_t i, double lambda, VectorRef y) const override;
  void apply_normal_displacement(std::size_t i, double dlambda, VectorRef y) const override;
  LinearLaw linear_law(std::size_t) const override { return contact::linear_law(p_.law); }
  SphereLineLayout sphere_line() const override;

 private:
  static double u(ConstVectorRef y, std::size_t b) { return y[static_cast<Eigen::Index>(2 * b)]; }
  static double v(ConstVectorRef y, std::size_t b) { return y[static_cast<Eigen::Index>(2 * b + 1)]; }
  // Adds `amount` along contact i's normal to entry `offset` (0 positions, 1 velocities) of its balls.
  void push_apart(std::size_t i, double amount, int offset, VectorRef y) const;
  BallStackParams p_;
};

}  // namespace contact
