#include "contact_ode/models/rigid/rigid_scene.hpp"

#include "contact_ode/models/rigid/rigid_resolution.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <tuple>

namespace contact::rigid {

RigidScene::RigidScene(std::string name, std::vector<RigidBody> bodies, Vec3 gravity, LawForPair law_for)
    : name_(std::move(name)), bodies_(std::move(bodies)), gravity_(std::move(gravity)) {
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(gravity_[i]))
      throw std::invalid_argument(
          fmt::format("scene '{}' gravity: value '{}' is out of range; accepted range finite values", name_,
                      gravity_[i]));
  for (auto& b : bodies_) {
    b.validate();
    b.orientation.normalize();
  }
  for (std::size_t a = 0; a < bodies_.size(); ++a)
    for (std::size_t b = a + 1; b < bodies_.size(); ++b) {
      const double inv = bodies_[a].inverse_mass + bodies_[b].inverse_mass;
      if (inv == 0) continue;  // two static bodies
      // A pair without a contact model would pass through each other without a word.
      if (candidate_count(bodies_[a], bodies_[b]) == 0)
        throw std::invalid_argument(fmt::format(
            "bodies '{}' and '{}': no contact between two cuboids is modelled (a pair needs a sphere, or "
            "a cuboid and a plane)",
            bodies_[a].name, bodies_[b].name));
      const ContactLaw law = law_for(pair_restitution(bodies_[a], bodies_[b]), 1.0 / inv);
      for (std::size_t k = 0; k < candidate_count(bodies_[a], bodies_[b]); ++k)
        candidates_.push_back({a, b, k, law});
    }
}

RigidScene::RigidScene(std::string name, std::vector<RigidBody> bodies, Vec3 gravity, ContactLaw law)
    : RigidScene(std::move(name), std::move(bodies), std::move(gravity),
                 [law](double, double) { return law; }) {}

RigidBody RigidScene::body_at(std::size_t j, ConstVectorRef y) const {
  const RigidBody& at_rest = bodies_[j];
  RigidBody body;  // all but the name, which no query about a contact reads
  body.shape = at_rest.shape;
  body.inverse_mass = at_rest.inverse_mass;
  body.inverse_inertia = at_rest.inverse_inertia;
  body.elasticity = at_rest.elasticity;
  const auto s = y.segment(static_cast<Eigen::Index>(j) * kStride, kStride);
  body.position = s.segment<3>(0);
  body.orientation = Quat(s[3], s[4], s[5], s[6]).normalized();
  body.velocity = s.segment<3>(7);
  body.angular_velocity = s.segment<3>(10);
  return body;
}

std::vector<RigidBody> RigidScene::unnamed_bodies_at(ConstVectorRef y) const {
  std::vector<RigidBody> out;
  out.reserve(bodies_.size());
  for (std::size_t j = 0; j < bodies_.size(); ++j) out.push_back(body_at(j, y));
  return out;
}

std::vector<RigidBody> RigidScene::bodies_at(ConstVectorRef y) const {
  std::vector<RigidBody> out = unnamed_bodies_at(y);
  for (std::size_t j = 0; j < out.size(); ++j) out[j].name = bodies_[j].name;
  return out;
}

void RigidScene::store_body(std::size_t j, const RigidBody& body, VectorRef y) const {
  auto s = y.segment(static_cast<Eigen::Index>(j) * kStride, kStride);
  const Quat& q = body.orientation;
  s.segment<3>(0) = body.position;
  s.segment<4>(3) << q.w(), q.x(), q.y(), q.z();
  s.segment<3>(7) = body.velocity;
  s.segment<3>(10) = body.angular_velocity;
}

void RigidScene::store(const std::vector<RigidBody>& bodies, VectorRef y) const {
  for (std::size_t j = 0; j < bodies.size(); ++j) store_body(j, bodies[j], y);
}

RigidScene::Local RigidScene::local(std::size_t i, ConstVectorRef y) const {
  const Candidate& c = candidates_[i];
  Local l{{body_at(c.a, y), body_at(c.b, y)}, {}};
  l.contact = contact_candidate(l.bodies, 0, 1, c.k);
  return l;
}

void RigidScene::store_local(std::size_t i, const Local& l, VectorRef y) const {
  store_body(candidates_[i].a, l.bodies[0], y);
  store_body(candidates_[i].b, l.bodies[1], y);
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
  return contact_candidate(bodies, c.a, c.b, c.k);
}

RigidContact RigidScene::contact(std::size_t i, ConstVectorRef y) const {
  RigidContact c = local(i, y).contact;
  std::tie(c.a, c.b) = pair(i);  // the scene's indices, not the local pair's
  return c;
}

double RigidScene::gap_rate(std::size_t i, ConstVectorRef y) const {
  const Local l = local(i, y);
  return normal_velocity(l.bodies, l.contact);
}

double RigidScene::switching(std::size_t i, ConstVectorRef y) const {
  const Local l = local(i, y);
  return contact::switching(candidates_[i].law, l.contact.penetration, -normal_velocity(l.bodies, l.contact));
}

double RigidScene::dissipated_power(std::size_t i, ConstVectorRef y) const {
  const Local l = local(i, y);
  return contact::dissipated_power(candidates_[i].law, l.contact.penetration,
                                   -normal_velocity(l.bodies, l.contact));
}

void RigidScene::rhs(double, ConstVectorRef y, const ContactModes& modes, VectorRef ydot) const {
  const auto bodies = unnamed_bodies_at(y);
  std::vector<Vec3> force(bodies.size(), Vec3::Zero()), torque(bodies.size(), Vec3::Zero());
  // Bodies resting on static ones: the direction into the support, and how fast it turns along the
  // body's motion (h' . v).
  std::vector<Vec3> held(bodies.size(), Vec3::Zero());
  std::vector<double> turn(bodies.size(), 0.0);
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    if (modes[i] == ContactMode::Resting) {
      const RigidContact c = contact(i, bodies);
      if (bodies[c.b].inverse_mass == 0) {  // a rests on b: cannot move along +n
        held[c.a] = c.normal;
        turn[c.a] = support_turn(i, bodies, c.a);
      }
      if (bodies[c.a].inverse_mass == 0) {  // b rests on a: cannot move along -n
        held[c.b] = -c.normal;
        turn[c.b] = -support_turn(i, bodies, c.b);
      }
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
    // Resting on a static body (event-driven rest): the support holds the gap's second derivative,
    // -(h . a + h' . v), at zero while that takes a push. On a flat support that removes the push
    // into it; on a curved one the support also bends the path (a ball sliding over a dome), and
    // lets go where gravity no longer supplies the bend (the dome's cos = 2/3 cos0). Without the
    // turn a ball slid off the dome along its tangent, pushed away by a support it had left.
    const double push = d.segment<3>(7).dot(held[i]) + turn[i];
    if (!held[i].isZero(0) && push > 0) d.segment<3>(7) -= push * held[i];
    if (!b.rotates()) continue;
    // q' = (1/2) (0, w) q for the stored (possibly not quite unit) q.
    const auto s = y.segment(static_cast<Eigen::Index>(i) * kStride, kStride);
    const Quat q(s[3], s[4], s[5], s[6]);
    const Quat wq = Quat(0, b.angular_velocity.x(), b.angular_velocity.y(), b.angular_velocity.z()) * q;
    d.segment<4>(3) << 0.5 * wq.w(), 0.5 * wq.x(), 0.5 * wq.y(), 0.5 * wq.z();
    d.segment<3>(10) = b.world_inverse_inertia() * (torque[i] - b.angular_velocity.cross(b.spin_momentum()));
  }
}

double RigidScene::support_turn(std::size_t i, const std::vector<RigidBody>& bodies, std::size_t j) const {
  const Candidate& c = candidates_[i];
  if (std::holds_alternative<Plane>(bodies[c.a == j ? c.b : c.a].shape)) return 0.0;  // a flat support
  std::array<RigidBody, 2> pair{bodies[c.a], bodies[c.b]};
  RigidBody& moving = pair[c.a == j ? 0 : 1];
  const Vec3 x = moving.position, v = moving.velocity;
  // A central difference along the path, a millionth of the body's reach to its contact point (a
  // sphere's radius): the normal turns over the support's radius of curvature, which is no shorter.
  const double reach = (x - contact_candidate(pair, 0, 1, c.k).point).norm();
  if (v.isZero(0) || !(reach > 0)) return 0.0;
  const double ds = 1e-6 * reach / v.norm();
  const auto normal_at = [&](double s) {
    moving.position = x + s * v;
    return contact_candidate(pair, 0, 1, c.k).normal;
  };
  return (normal_at(ds) - normal_at(-ds)).dot(v) / (2 * ds);
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
  return energy_without_springs(y) + engaged_elastic_energy(y);
}

double RigidScene::energy_without_springs(ConstVectorRef y) const {
  const auto bodies = unnamed_bodies_at(y);
  double E = 0;
  for (const auto& b : bodies) {
    E += b.kinetic_energy();
    if (b.inverse_mass > 0) E -= gravity_.dot(b.position) / b.inverse_mass;
  }
  return E;
}

double RigidScene::mean_mass() const {
  double sum = 0;
  int moving = 0;
  for (const auto& b : bodies_)
    if (b.inverse_mass > 0) sum += 1.0 / b.inverse_mass, ++moving;
  return moving ? sum / moving : 1.0;  // nothing moves: nothing to scale, kilograms do
}

double RigidScene::elastic_energy(std::size_t i, ConstVectorRef y) const {
  return stored_energy(candidates_[i].law, local(i, y).contact.penetration);
}

double RigidScene::restitution(std::size_t i) const {
  return pair_restitution(bodies_[candidates_[i].a], bodies_[candidates_[i].b]);
}

void RigidScene::project(std::size_t i, VectorRef y) const {
  Local l = local(i, y);
  rigid::project(l.bodies, l.contact, ProjectionShare::InverseMass);
  store_local(i, l, y);
}

double RigidScene::apply_impulse(std::size_t i, double e, VectorRef y) const {
  Local l = local(i, y);
  const double J = rigid::apply_impulse(l.bodies, l.contact, e);
  store_local(i, l, y);
  return J;
}

double RigidScene::inverse_mass(std::size_t i, ConstVectorRef y) const {
  const Local l = local(i, y);
  return normal_inverse_mass(l.bodies, l.contact);
}

void RigidScene::apply_normal_impulse(std::size_t i, double lambda, VectorRef y) const {
  Local l = local(i, y);
  rigid::apply_normal_impulse(l.bodies, l.contact, lambda);
  store_local(i, l, y);
}

void RigidScene::apply_normal_displacement(std::size_t i, double dlambda, VectorRef y) const {
  Local l = local(i, y);
  rigid::apply_normal_displacement(l.bodies, l.contact, dlambda);
  store_local(i, l, y);
}

bool RigidScene::holds_at_rest(std::size_t i) const {
  return bodies_[candidates_[i].a].inverse_mass == 0 || bodies_[candidates_[i].b].inverse_mass == 0;
}

void RigidScene::settle(std::size_t i, VectorRef y) const {
  // The normal impulse that leaves no relative normal velocity, approaching or leaving (a bounce
  // slower than the rest speed rests too), then projection removes the overlap. The impact's rule,
  // an impulse only on approach, left a rested ball its bounce: held against gravity, it climbed at
  // that speed for good (rubber-steel's steel ball at 1.2e-5 m/s, the energy ledger running off).
  Local l = local(i, y);
  const double denom = rigid::normal_inverse_mass(l.bodies, l.contact);
  if (denom > 0)
    rigid::apply_normal_impulse(l.bodies, l.contact, -rigid::normal_velocity(l.bodies, l.contact) / denom);
  rigid::project(l.bodies, l.contact, ProjectionShare::InverseMass);
  store_local(i, l, y);
}

}  // namespace contact::rigid
