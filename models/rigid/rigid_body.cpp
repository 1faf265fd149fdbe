#include "contact_ode/models/rigid/rigid_body.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace contact::rigid {

namespace {

void require(bool ok, const std::string& what, double value, const std::string& range) {
  if (!ok)
    throw std::invalid_argument(
        fmt::format("{}: value '{}' is out of range; accepted range {}", what, value, range));
}

void validate_shape(const RigidBody& b) {
  if (const auto* s = std::get_if<Sphere>(&b.shape))
    require(std::isfinite(s->radius) && s->radius > 0, b.name + " radius", s->radius, "(0, inf)");
  if (const auto* c = std::get_if<Cuboid>(&b.shape))
    for (int i = 0; i < 3; ++i)
      require(std::isfinite(c->half_extents[i]) && c->half_extents[i] > 0, b.name + " half extent",
              c->half_extents[i], "(0, inf)");
  if (const auto* p = std::get_if<Plane>(&b.shape)) {
    // Its geometry is its normal and offset, not the body's position: a plane cannot move.
    require(b.inverse_mass == 0, b.name + " inverse mass (a plane)", b.inverse_mass, "0: a plane is static");
    const double length = p->normal.norm();
    require(p->normal.allFinite() && std::abs(length - 1) <= 1e-12, b.name + " plane normal length", length,
            "1 (a unit vector, to 1e-12; RigidBody::plane normalises)");
    require(std::isfinite(p->offset), b.name + " plane offset", p->offset, "finite values");
  }
}

}  // namespace

RigidBody RigidBody::sphere(std::string name, double mass, double radius, double elasticity) {
  RigidBody b{std::move(name), Sphere{radius}};
  require(std::isfinite(mass) && mass > 0, b.name + " mass", mass, "(0, inf)");
  require(std::isfinite(radius) && radius > 0, b.name + " radius", radius, "(0, inf)");
  b.inverse_mass = 1.0 / mass;
  b.inverse_inertia = Mat3::Identity() / (0.4 * mass * radius * radius);
  b.elasticity = elasticity;
  return b;
}

RigidBody RigidBody::cuboid(std::string name, double mass, const Vec3& h, double elasticity) {
  RigidBody b{std::move(name), Cuboid{h, false}};
  require(std::isfinite(mass) && mass > 0, b.name + " mass", mass, "(0, inf)");
  for (int i = 0; i < 3; ++i)
    require(std::isfinite(h[i]) && h[i] > 0, b.name + " half extent", h[i], "(0, inf)");
  const Vec3 s = 2 * h;  // full sides
  b.inverse_mass = 1.0 / mass;
  b.inverse_inertia =
      Vec3(12 / (mass * (s[1] * s[1] + s[2] * s[2])), 12 / (mass * (s[0] * s[0] + s[2] * s[2])),
           12 / (mass * (s[0] * s[0] + s[1] * s[1])))
          .asDiagonal();
  b.elasticity = elasticity;
  return b;
}

RigidBody RigidBody::aabb(std::string name, double mass, const Vec3& h, double elasticity) {
  RigidBody b = cuboid(std::move(name), mass, h, elasticity);
  std::get<Cuboid>(b.shape).axis_aligned = true;
  b.inverse_inertia.setZero();
  return b;
}

RigidBody RigidBody::plane(std::string name, const Vec3& normal, double offset, double elasticity) {
  require(normal.allFinite() && normal.norm() > 0, name + " plane normal length", normal.norm(), "(0, inf)");
  RigidBody b{std::move(name), Plane{normal.normalized(), offset}};
  b.elasticity = elasticity;
  return b;
}

bool RigidBody::rotates() const {
  // Infinite mass is the tutorial's static object, which turns no more than it moves: the sphere and
  // cuboid makers give every body an inertia, and one made static by its inverse mass alone kept it
  // (a static box hit off its centre took up a turn it never made, and the ball came back at 1.79
  // m/s for 2).
  const auto* c = std::get_if<Cuboid>(&shape);
  return inverse_mass > 0 && !(c && c->axis_aligned) && !inverse_inertia.isZero(0);
}

Mat3 RigidBody::world_inverse_inertia() const {
  if (!rotates()) return Mat3::Zero();
  const Mat3 R = orientation.toRotationMatrix();
  return R * inverse_inertia * R.transpose();
}

// I w by solving I^-1 x = w (LDLT: I^-1 is symmetric positive definite, validate() checks it). The
// closed-form 3x3 inverse divides by a determinant, a product of three entries, which overflows or
// underflows for bodies of 1e-100 or 1e100 kg of decimetres, making the energy NaN while every
// entry was finite; the factorisation's pivots stay the size of the entries.
Vec3 RigidBody::spin_momentum() const {
  if (!rotates()) return Vec3::Zero();
  return world_inverse_inertia().ldlt().solve(angular_velocity);
}

double RigidBody::kinetic_energy() const {
  double E = inverse_mass > 0 ? 0.5 * velocity.squaredNorm() / inverse_mass : 0.0;
  return E + 0.5 * angular_velocity.dot(spin_momentum());
}

Vec3 RigidBody::momentum() const { return inverse_mass > 0 ? Vec3(velocity / inverse_mass) : Vec3::Zero(); }

Vec3 RigidBody::angular_momentum(const Vec3& about) const {
  Vec3 L = (position - about).cross(momentum());
  return L + spin_momentum();
}

void RigidBody::validate() const {
  require(std::isfinite(inverse_mass) && inverse_mass >= 0, name + " inverse mass", inverse_mass, "[0, inf)");
  require(std::isfinite(elasticity) && elasticity >= 0, name + " elasticity", elasticity, "[0, inf)");
  const double qn = orientation.coeffs().norm();
  require(orientation.coeffs().allFinite() && qn > 0, name + " quaternion norm", qn, "(0, inf), finite");
  // Each vector by name, its first entry that is not finite as the value: "red state finite: value
  // '0'" said neither which nor what (a ball placed 2 radii out, radius 1e308).
  const auto require_finite = [&](const Vec3& v, const char* what) {
    for (int i = 0; i < 3; ++i) require(std::isfinite(v[i]), name + " " + what, v[i], "finite values");
  };
  require_finite(position, "position");
  require_finite(velocity, "velocity");
  require_finite(angular_velocity, "angular velocity");
  validate_shape(*this);
  for (Eigen::Index i = 0; i < 9; ++i)
    require(std::isfinite(inverse_inertia(i)), name + " inverse inertia", inverse_inertia(i),
            "finite values");
  // A turning body's inertia is inverted (its angular momentum): symmetric positive definite, or zero
  // for a body that does not turn.
  if (rotates()) {
    const double size = inverse_inertia.cwiseAbs().maxCoeff();
    const double asymmetry = (inverse_inertia - inverse_inertia.transpose()).cwiseAbs().maxCoeff();
    require(asymmetry <= 1e-12 * size, name + " inverse inertia asymmetry", asymmetry,
            "0 (a symmetric matrix, to 1e-12 of its largest entry)");
    const double lowest =
        Eigen::SelfAdjointEigenSolver<Mat3>(inverse_inertia, Eigen::EigenvaluesOnly).eigenvalues()[0];
    require(lowest > 0, name + " inverse inertia's smallest eigenvalue", lowest,
            "(0, inf), or the zero matrix for a body that does not turn");
  }
  // Infinite mass never moves (its state has no derivatives), so a velocity would be one it does not
  // have: contacts would see a wall that moves and stays.
  if (inverse_mass == 0) {
    require(velocity.isZero(0), name + " speed (infinite mass)", velocity.norm(),
            "0: a static body never moves");
    require(angular_velocity.isZero(0), name + " angular speed (infinite mass)", angular_velocity.norm(),
            "0: a static body never turns");
  }
}

}  // namespace contact::rigid
