#pragma once
// Rigid bodies for the 3D scenes, in the tutorial's terms: inverse mass (0: infinite mass, a body
// that neither moves nor turns), inverse inertia tensor in the body frame (world: R I^-1 R^T),
// elasticity (a pair's restitution is the product of the two), position, unit orientation
// quaternion, linear and angular velocity (world frame).
// Shapes: sphere, cuboid (an oriented box), axis-aligned box (never rotates: its inverse inertia
// is zero and, as the tutorial does, its lever arms are taken as zero), static plane.
#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <string>
#include <variant>

namespace contact::rigid {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

struct Sphere {
  double radius;
};
struct Cuboid {
  Vec3 half_extents;
  bool axis_aligned = false;  // an AABB: never rotates
};
struct Plane {
  Vec3 normal;    // unit; the solid side is behind it
  double offset;  // points x with normal . x = offset lie on the plane
};
using Shape = std::variant<Sphere, Cuboid, Plane>;

// RigidScene::body_at copies every field but the name by hand (rigid_scene.cpp): a field added
// here goes there too.
struct RigidBody {
  std::string name;
  Shape shape;
  double inverse_mass = 0.0;
  Mat3 inverse_inertia = Mat3::Zero();  // body frame
  double elasticity = 1.0;
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();

  // Uniform solid sphere: I = (2/5) m r^2.
  static RigidBody sphere(std::string name, double mass, double radius, double elasticity);
  // Uniform solid cuboid: I = (m/12) diag(b^2 + c^2, a^2 + c^2, a^2 + b^2) for full sides a, b, c.
  static RigidBody cuboid(std::string name, double mass, const Vec3& half_extents, double elasticity);
  static RigidBody aabb(std::string name, double mass, const Vec3& half_extents, double elasticity);
  static RigidBody plane(std::string name, const Vec3& normal, double offset, double elasticity);

  bool rotates() const;
  Mat3 world_inverse_inertia() const;
  // I w, the spin's angular momentum (zero for a body that does not turn).
  Vec3 spin_momentum() const;
  // Velocity of the material point at world offset r from the centre: v + w x r.
  Vec3 point_velocity(const Vec3& r) const { return velocity + angular_velocity.cross(r); }
  double kinetic_energy() const;
  Vec3 momentum() const;                           // m v (zero for infinite mass)
  Vec3 angular_momentum(const Vec3& about) const;  // (x - about) x m v + I w

  // Throws std::invalid_argument naming the field, the value and the accepted range: shape
  // dimensions, a static plane of unit normal, a finite inverse inertia (symmetric positive definite
  // where the body turns), and a body of infinite mass at rest.
  void validate() const;
};

}  // namespace contact::rigid
