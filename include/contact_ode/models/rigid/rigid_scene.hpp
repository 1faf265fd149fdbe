#pragma once
// A scene of rigid bodies as a MechanicalSystem, so the three paradigms run it unchanged.
//   state, per body: x (3), q (4: w, x, y, z), v (3), w (3, world frame)      13 numbers
//   x' = v,  q' = (1/2) (0, w) q,  v' = g + f / m,  w' = I_w^-1 (tau - w x I_w w)  (Euler's
//   equations in the world frame, I_w = R I R^T); bodies of infinite mass have zero derivatives,
//   bodies that do not rotate zero angular ones.
//   contacts: every candidate of every pair (rigid_contacts.hpp), fixed at construction; the gap
//   is -penetration, its rate the relative normal velocity at the contact point.
//   penalty: the contact law's force F(delta, delta_dot) pushes b along +n and a along -n at the
//   contact point, with torques r x f on each.
//   energy: kinetic + gravitational (-m g.x) + the springs' stored energy.
//   resting (event-driven rest): a body resting on a static body is held on it as a support force
//   would hold it: the gap's second derivative is held at zero while that takes a push (flat: the
//   push into the support removed; curved: the path bent with it), and the support lets go where
//   it would have to pull. Exact for a sphere; a resting cuboid's turn is not held. Resting
//   between two moving bodies is not modelled (treated as free).
// No analytic Jacobian (rotations make it long; implicit integrators use difference quotients,
// which test_rigid_scene checks). The rotation uses q / |q|; normalize() restores unit
// quaternions after fixed steps.
#include "contact_ode/models/contact_law.hpp"
#include "contact_ode/models/mechanical_system.hpp"
#include "contact_ode/models/rigid/rigid_contacts.hpp"

#include <array>
#include <functional>

namespace contact::rigid {

class RigidScene final : public MechanicalSystem, public NormalImpulses {
 public:
  // Each pair's penalty law comes from `law_for(e, m_eff)`: its restitution (the product of
  // elasticities) and effective mass 1 / (m_a^-1 + m_b^-1).
  using LawForPair = std::function<ContactLaw(double e, double m_eff)>;
  RigidScene(std::string name, std::vector<RigidBody> bodies, Vec3 gravity, LawForPair law_for);
  // Every pair with the same law.
  RigidScene(std::string name, std::vector<RigidBody> bodies, Vec3 gravity, ContactLaw law);

  static constexpr Eigen::Index kStride = 13;
  std::vector<RigidBody> bodies_at(ConstVectorRef y) const;
  void store(const std::vector<RigidBody>& bodies, VectorRef y) const;
  const std::vector<RigidBody>& bodies() const { return bodies_; }
  const Vec3& gravity() const { return gravity_; }
  // Which bodies candidate contact i joins.
  std::pair<std::size_t, std::size_t> pair(std::size_t i) const {
    return {candidates_[i].a, candidates_[i].b};
  }

  std::string name() const override { return name_; }
  Mask position_mask() const override;
  std::size_t state_size() const override { return bodies_.size() * kStride; }
  Vector initial_state() const override;
  std::vector<std::string> state_labels() const override;

  void rhs(double t, ConstVectorRef y, const ContactModes& modes, VectorRef ydot) const override;
  bool has_jacobian() const override { return false; }
  void jacobian(double, ConstVectorRef, const ContactModes&, SparseMatrix&) const override;
  void normalize(VectorRef y) const override;
  double energy(ConstVectorRef y) const override;
  double energy_without_springs(ConstVectorRef y) const override;
  double mean_mass() const override;  // of the bodies of finite mass

  std::size_t contact_count() const override { return candidates_.size(); }
  double gap(std::size_t i, ConstVectorRef y) const override { return -contact(i, y).penetration; }
  double gap_rate(std::size_t i, ConstVectorRef y) const override;
  double switching(std::size_t i, ConstVectorRef y) const override;
  double overlap_extent(std::size_t i) const override {
    return rigid::overlap_extent(bodies_[candidates_[i].a], bodies_[candidates_[i].b]);
  }
  bool releases_while_overlapping(std::size_t i) const override {
    return contact::releases_while_overlapping(candidates_[i].law);
  }
  double dissipated_power(std::size_t i, ConstVectorRef y) const override;
  double elastic_energy(std::size_t i, ConstVectorRef y) const override;

  double restitution(std::size_t i) const override;
  void project(std::size_t i, VectorRef y) const override;
  double apply_impulse(std::size_t i, double e, VectorRef y) const override;
  void settle(std::size_t i, VectorRef y) const override;
  bool holds_at_rest(std::size_t i) const override;

  double inverse_mass(std::size_t i, ConstVectorRef y) const override;
  void apply_normal_impulse(std::size_t i, double lambda, VectorRef y) const override;
  void apply_normal_displacement(std::size_t i, double dlambda, VectorRef y) const override;
  LinearLaw linear_law(std::size_t i) const override { return contact::linear_law(candidates_[i].law); }

  RigidContact contact(std::size_t i, ConstVectorRef y) const;
  RigidContact contact(std::size_t i, const std::vector<RigidBody>& bodies) const;

 private:
  struct Candidate {
    std::size_t a, b, k;  // bodies, and which of their candidates (a cuboid vertex)
    ContactLaw law;       // the pair's
  };
  // Candidate i's two bodies alone (at 0 and 1) and their contact in those indices. A query about
  // one contact copies two bodies, not the scene: the root functions ask about every contact, and
  // copying every body for each made a scene's root evaluation cost O(bodies x contacts).
  struct Local {
    std::array<RigidBody, 2> bodies;  // on the stack: these queries run at every step and root check
    RigidContact contact;
  };
  Local local(std::size_t i, ConstVectorRef y) const;
  void store_local(std::size_t i, const Local& l, VectorRef y) const;
  // Body j, or every body, in state y, without the name: the queries at every step and root check
  // never read it, and without it body_at ran a quarter fewer instructions (callgrind on
  // rigid_impacts). bodies_at adds the names.
  RigidBody body_at(std::size_t j, ConstVectorRef y) const;
  std::vector<RigidBody> unnamed_bodies_at(ConstVectorRef y) const;
  void store_body(std::size_t j, const RigidBody& body, VectorRef y) const;
  // How fast contact i's normal (from a to b) turns as body j moves along its velocity, n' . v:
  // zero on a plane, |v_t|^2 / d for a sphere d from the centre of a static sphere.
  double support_turn(std::size_t i, const std::vector<RigidBody>& bodies, std::size_t j) const;

  std::string name_;
  std::vector<RigidBody> bodies_;
  Vec3 gravity_;
  std::vector<Candidate> candidates_;
};

}  // namespace contact::rigid
