#pragma once
// Ball drop: a point mass m [kg] falls under gravity g [m/s^2] from height h0 [m] with initial
// vertical velocity v0 [m/s] onto the rigid floor y = 0.
//
//   state  y = [x, v]          height [m] and vertical velocity [m/s]
//   gap    x,  gap rate v      overlap delta = -x, its rate delta_dot = -v
//   free       x' = v, v' = -g
//   penalty    x' = v, v' = -g + F(delta, delta_dot)/m     (F from the contact law)
//   resting    x' = 0, v' = 0
//   energy     m v^2/2 + m g x + stored spring energy
//
// Impulses: the floor has inverse mass 0, so projection moves the ball by the full overlap and
// the seed's impulse J = -(1+e) v / m^-1 gives v+ = -e v.
#include "contact_ode/models/contact_law.hpp"
#include "contact_ode/models/mechanical_system.hpp"

namespace contact {

struct BallDropParams {
  double m = 1.0;   // mass [kg]
  double g = 9.81;  // gravity [m/s^2]
  double h0 = 1.0;  // initial height [m]
  double v0 = 0.0;  // initial vertical velocity [m/s] (negative: downwards)
  double e = 0.8;   // Newton restitution for impulses
  ContactLaw law = Hooke{1e5};
};

// The speed at the floor of a ball released at height h0 with vertical speed v0 under gravity g,
// sqrt(v0^2 + 2 g h0), without underflow or overflow (a drop of 1e-165 m under gravity scaled
// alike: its terms are zero, and the speed came out 0; of 1e157 m: they overflow) [m/s].
double impact_speed(double h0, double v0, double g);

class BallDrop final : public MechanicalSystem,
                       public AnalyticFlight,
                       public NormalImpulses,
                       public SphereLine {
 public:
  explicit BallDrop(BallDropParams p) : p_(std::move(p)) {}
  const BallDropParams& params() const { return p_; }

  std::string name() const override { return "ball-drop"; }
  Mask position_mask() const override { return Mask{{true, false}}; }
  std::size_t state_size() const override { return 2; }
  Vector initial_state() const override { return Vector{{p_.h0, p_.v0}}; }
  std::vector<std::string> state_labels() const override { return {"y_m", "v_mps"}; }

  void rhs(double t, ConstVectorRef y, const ContactModes& modes, VectorRef ydot) const override;
  void jacobian(double t, ConstVectorRef y, const ContactModes& modes, SparseMatrix& J) const override;
  double energy(ConstVectorRef y) const override;
  double energy_without_springs(ConstVectorRef y) const override;
  double mean_mass() const override { return p_.m; }

  std::size_t contact_count() const override { return 1; }
  double gap(std::size_t, ConstVectorRef y) const override { return y[0]; }
  double gap_rate(std::size_t, ConstVectorRef y) const override { return y[1]; }
  double switching(std::size_t, ConstVectorRef y) const override {
    return contact::switching(p_.law, -y[0], -y[1]);
  }
  bool releases_while_overlapping(std::size_t) const override {
    return contact::releases_while_overlapping(p_.law);
  }

  double dissipated_power(std::size_t, ConstVectorRef y) const override {
    return contact::dissipated_power(p_.law, -y[0], -y[1]);
  }
  double elastic_energy(std::size_t, ConstVectorRef y) const override { return stored_energy(p_.law, -y[0]); }
  double restitution(std::size_t) const override { return p_.e; }
  void project(std::size_t i, VectorRef y) const override;
  double apply_impulse(std::size_t i, double e, VectorRef y) const override;
  void settle(std::size_t, VectorRef y) const override { y << 0.0, 0.0; }

  double inverse_mass(std::size_t, ConstVectorRef) const override { return 1.0 / p_.m; }
  void apply_normal_impulse(std::size_t, double lambda, VectorRef y) const override { y[1] += lambda / p_.m; }
  void apply_normal_displacement(std::size_t, double dlambda, VectorRef y) const override {
    y[0] += dlambda / p_.m;
  }
  LinearLaw linear_law(std::size_t) const override { return contact::linear_law(p_.law); }

  // A sphere of radius 0.1 m (the point mass has none; rotation never enters) on the floor plane.
  SphereLineLayout sphere_line() const override;
  void propagate(ConstVectorRef y0, double dt, VectorRef y) const override;
  double time_to_impact(std::size_t i, ConstVectorRef y0) const override;
  double time_to_apex(std::size_t i, ConstVectorRef y0) const override;

 private:
  BallDropParams p_;
};

}  // namespace contact
