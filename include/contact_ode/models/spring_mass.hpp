#pragma once
// The free spring: a mass m [kg] on a bilateral Hooke spring k [N/m], no gravity, no contact.
//   y = [x, v],  x' = v,  v' = -(k/m) x,  energy (m v^2 + k x^2)/2,  omega = sqrt(k/m).
// The harmonic oscillator on which the fixed-step schemes' energy behaviour has closed forms.
// Dynamics only: it has no contacts, so it offers neither contact geometry nor an impulse map.
#include "contact_ode/models/mechanical_system.hpp"

#include <cmath>

namespace contact {

class SpringMass final : public Dynamics {
 public:
  SpringMass(double m, double k, double x0, double v0) : m_(m), k_(k), x0_(x0), v0_(v0) {}
  double omega() const { return std::sqrt(k_ / m_); }

  std::string name() const override { return "spring-mass"; }
  Mask position_mask() const override { return Mask{{true, false}}; }
  std::size_t state_size() const override { return 2; }
  Vector initial_state() const override { return Vector{{x0_, v0_}}; }
  std::vector<std::string> state_labels() const override { return {"x_m", "v_mps"}; }

  void rhs(double, ConstVectorRef y, const ContactModes&, VectorRef ydot) const override {
    ydot << y[1], -(k_ / m_) * y[0];
  }
  void jacobian(double, ConstVectorRef, const ContactModes&, SparseMatrix& J) const override {
    const Triplet entries[] = {{0, 0, 0.0}, {0, 1, 1.0}, {1, 0, -(k_ / m_)}, {1, 1, 0.0}};
    J.resize(2, 2);
    J.setFromTriplets(std::begin(entries), std::end(entries));
  }
  double mean_mass() const override { return m_; }
  double energy(ConstVectorRef y) const override { return 0.5 * (m_ * y[1] * y[1] + k_ * y[0] * y[0]); }

 private:
  double m_, k_, x0_, v0_;
};

}  // namespace contact
