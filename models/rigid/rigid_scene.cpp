#include "contact_ode/models/rigid/rigid_scene.hpp"

#include "contact_ode/models/rigid/rigid_resolution.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace contact::rigid {

RigidScene::RigidScene(std::string name, std::vector<RigidBody> bodies, Vec3 gravity, LawForPair law_for)
    : name_(std::move(name)), bodies_(std::move(bodies)), gravity_(std::move(gravity)) {
  for (auto& b : bodies_) {
    b.validate();
    b.orientation.normalize();
  }
  for (std::size_t a = 0; a < bodies_.size(); ++a)
    for (std::size_t b = a + 1; b < bodies_.size(); ++b) {
      const double inv = bodies_[a].inverse_mass + bodies_[b].inverse_mass;
      if (inv == 0) continue;  // two static bodies
      const ContactLaw law = law_for(pair_restitution(bodies_[a], bodies_[b]), 1.0 / inv);
      const auto list = contact_candidates(bodies_, a, b);
      for (std::size_t k = 0; k < list.size(); ++k) candidates_.push_back({a, b, k, law});
    }
}

RigidScene::RigidScene(std::string name, std::vector<RigidBody> bodies, Vec3 gravity, ContactLaw law)
    : RigidScene(std::move(name), std::move(bodies), std::move(gravity),
                 [law](double, double) { return law; }) {}

std::vector<RigidBody> RigidScene::bodies_at(ConstVectorRef y) const {
  std::vector<RigidBody> out = bodies_;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto s = y.segment(static_cast<Eigen::Index>(i) * kStride, kStride);
    out[i].position = s.segment<3>(0);
    out[i].orientation = Quat(s[3], s[4], s[5], s[6]).normalized();
    out[i].velocity = s.segment<3>(7);
    out[i].angular_velocity = s.segment<3>(10);
  }
  return out;
}

void RigidScene::store(const std::vector<RigidBody>& bodies, VectorRef y) const {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    auto s = y.segment(static_cast<Eigen::Index>(i) * kStride, kStride);
    const Quat& q = bodies[i].orientation;
    s.segment<3>(0) = bodies[i].position;
    s.segment<4>(3) << q.w(), q.x(), q.y(), q.z();
    s.segment<3>(7) = bodies[i].velocity;
    s.segment<3>(10) = bodies[i].angular_velocity;
  }
}

Mask RigidScene::position_mask() const {
  Mask m(static_cast<Eigen::Index>(state_size()));
  for (Eigen::Index k = 0; k < m.size(); ++k) m[k] = k % kStride < 7;  // x and q
  return m;
}

Vector RigidScene::initial_state() const {
  Vector y(static_cast<Eigen::Index>(state_size()));
  store(bodies_, y);
  return y;
}

std::vector<std::string> RigidScene::state_labels() const {
  std::vector<std::string> labels;
  for (const auto& b : bodies_)
    for (const char* f : {"x_m", "y_m", "z_m", "qw", "qx", "qy", "qz", "vx_mps", "vy_mps", "vz_mps",
                          "wx_radps", "wy_radps", "wz_radps"})
      labels.push_back(b.name + "_" + f);
  return labels;
}

RigidContact RigidScene::contact(std::size_t i, const std::vector<RigidBody>& bodies) const {
  const Candidate& c = candidates_[i];
  return contact_candidates(bodies, c.a, c.b)[c.k];
}

RigidContact RigidScene::contact(std::size_t i, ConstVectorRef y) const { return contact(i, bodies_at(y)); }

double RigidScene::gap_rate(std::size_t i, ConstVectorRef y) const {
  const auto bodies = bodies_at(y);
  return normal_velocity(bodies, contact(i, bodies));
}

double RigidScene::switching(std::size_t i, ConstVectorRef y) const {
  const auto bodies = bodies_at(y);
  const RigidContact c = contact(i, bodies);
  return contact::switching(candidates_[i].law, c.penetration, -normal_velocity(bodies, c));
}

double RigidScene::dissipated_power(std::size_t i, ConstVectorRef y) const {
  const auto bodies = bodies_at(y);
  const RigidContact c = contact(i, bodies);
  return contact::dissipated_power(candidates_[i].law, c.penetration, -normal_velocity(bodies, c));
}

void RigidScene::rhs(double, ConstVectorRef y, const ContactModes& modes, VectorRef ydot) const {
  const auto bodies = bodies_at(y);
  std::vector<Vec3> force(bodies.size(), Vec3::Zero()), torque(bodies.size(), Vec3::Zero());
  std::vector<Vec3> held(bodies.size(), Vec3::Zero());  // resting normals of bodies on static ones
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    if (modes[i] == ContactMode::Resting) {
      const RigidContact c = contact(i, bodies);
      if (bodies[c.b].inverse_mass == 0) held[c.a] = c.normal;   // a rests on b: cannot move along +n
      if (bodies[c.a].inverse_mass == 0) held[c.b] = -c.normal;  // b rests on a: cannot move along -n
    }
    if (modes[i] != ContactMode::Penalty) continue;
    const RigidContact c = contact(i, bodies);
    const double F = contact::force(candidates_[i].law, c.penetration, -normal_velocity(bodies, c));
    const Vec3 f = F * c.normal;  // on b; -f on a
    force[c.b] += f;
    force[c.a] -= f;
    torque[c.b] += c.r_b.cross(f);
    torque[c.a] -= c.r_a.cross(f);
  }
  ydot.setZero();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const RigidBody& b = bodies[i];
    if (b.inverse_mass == 0) continue;
    auto d = ydot.segment(static_cast<Eigen::Index>(i) * kStride, kStride);
    d.segment<3>(0) = b.velocity;
    d.segment<3>(7) = gravity_ + b.inverse_mass * force[i];
    // Resting on a static body (event-driven rest): the push into it is held by the support.
    if (!held[i].isZero(0) && d.segment<3>(7).dot(held[i]) > 0)
      d.segment<3>(7) -= d.segment<3>(7).dot(held[i]) * held[i];
    if (!b.rotates()) continue;
    // q' = (1/2) (0, w) q for the stored (possibly not quite unit) q.
    const auto s = y.segment(static_cast<Eigen::Index>(i) * kStride, kStride);
    const Quat q(s[3], s[4], s[5], s[6]);
    const Quat wq = Quat(0, b.angular_velocity.x(), b.angular_velocity.y(), b.angular_velocity.z()) * q;
    d.segment<4>(3) << 0.5 * wq.w(), 0.5 * wq.x(), 0.5 * wq.y(), 0.5 * wq.z();
    const Mat3 Iinv = b.world_inverse_inertia();
    const Vec3 L = Iinv.inverse() * b.angular_velocity;
    d.segment<3>(10) = Iinv * (torque[i] - b.angular_velocity.cross(L));
  }
}

void RigidScene::jacobian(double, ConstVectorRef, const ContactModes&, SparseMatrix&) const {
  throw std::logic_error("RigidScene has no analytic Jacobian; use difference quotients");
}

void RigidScene::normalize(VectorRef y) const {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    auto q = y.segment<4>(static_cast<Eigen::Index>(i) * kStride + 3);
    q /= q.norm();
  }
}

double RigidScene::energy(ConstVectorRef y) const {
  const auto bodies = bodies_at(y);
  double E = 0;
  for (const auto& b : bodies) {
    E += b.kinetic_energy();
    if (b.inverse_mass > 0) E -= gravity_.dot(b.position) / b.inverse_mass;
  }
  return E + engaged_elastic_energy(y);
}

double RigidScene::elastic_energy(std::size_t i, ConstVectorRef y) const {
  return stored_energy(candidates_[i].law, contact(i, y).penetration);
}

double RigidScene::restitution(std::size_t i) const {
  return pair_restitution(bodies_[candidates_[i].a], bodies_[candidates_[i].b]);
}

void RigidScene::project(std::size_t i, VectorRef y) const {
  auto bodies = bodies_at(y);
  rigid::project(bodies, contact(i, bodies), ProjectionShare::InverseMass);
  store(bodies, y);
}

void RigidScene::apply_impulse(std::size_t i, double e, VectorRef y) const {
  auto bodies = bodies_at(y);
  rigid::apply_impulse(bodies, contact(i, bodies), e);
  store(bodies, y);
}

double RigidScene::inverse_mass(std::size_t i, ConstVectorRef y) const {
  const auto bodies = bodies_at(y);
  return normal_inverse_mass(bodies, contact(i, bodies));
}

void RigidScene::apply_normal_impulse(std::size_t i, double lambda, VectorRef y) const {
  auto bodies = bodies_at(y);
  rigid::apply_normal_impulse(bodies, contact(i, bodies), lambda);
  store(bodies, y);
}

void RigidScene::apply_normal_displacement(std::size_t i, double dlambda, VectorRef y) const {
  auto bodies = bodies_at(y);
  rigid::apply_normal_displacement(bodies, contact(i, bodies), dlambda);
  store(bodies, y);
}

void RigidScene::settle(std::size_t i, VectorRef y) const {
  // A perfectly inelastic impulse removes the approach; projection removes the overlap.
  auto bodies = bodies_at(y);
  const RigidContact c = contact(i, bodies);
  rigid::apply_impulse(bodies, c, 0.0);
  rigid::project(bodies, c, ProjectionShare::InverseMass);
  store(bodies, y);
}

}  // namespace contact::rigid
