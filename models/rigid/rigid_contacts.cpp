#include "contact_ode/models/rigid/rigid_contacts.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace contact::rigid {

namespace {

Vec3 lever(const RigidBody& body, const Vec3& point) {
  return body.rotates() ? Vec3(point - body.position) : Vec3::Zero();
}

RigidContact make(std::span<const RigidBody> bodies, std::size_t a, std::size_t b, const Vec3& point,
                  const Vec3& normal, double penetration) {
  return {a, b, point, normal, penetration, lever(bodies[a], point), lever(bodies[b], point)};
}

RigidContact flip(std::span<const RigidBody> bodies, RigidContact c) {
  return make(bodies, c.b, c.a, c.point, -c.normal, c.penetration);
}

RigidContact sphere_sphere(std::span<const RigidBody> bodies, std::size_t a, std::size_t b) {
  const double ra = std::get<Sphere>(bodies[a].shape).radius, rb = std::get<Sphere>(bodies[b].shape).radius;
  const Vec3 d = bodies[b].position - bodies[a].position;
  const double dist = d.norm();
  const Vec3 n = dist > 0 ? Vec3(d / dist) : Vec3::UnitZ();
  const double pen = ra + rb - dist;
  return make(bodies, a, b, bodies[a].position + n * (ra - 0.5 * pen), n, pen);
}

// Sphere a against plane b: the normal points from the sphere into the plane's solid side.
RigidContact sphere_plane(std::span<const RigidBody> bodies, std::size_t a, std::size_t b) {
  const double r = std::get<Sphere>(bodies[a].shape).radius;
  const Plane& p = std::get<Plane>(bodies[b].shape);
  const double height = p.normal.dot(bodies[a].position) - p.offset;
  const double pen = r - height;
  return make(bodies, a, b, bodies[a].position - p.normal * (r - 0.5 * pen), -p.normal, pen);
}

// Sphere a against cuboid b, from the box's closest point to the sphere's centre.
RigidContact sphere_cuboid(std::span<const RigidBody> bodies, std::size_t a, std::size_t b) {
  const RigidBody& box = bodies[b];
  const Vec3 h = std::get<Cuboid>(box.shape).half_extents;
  const double r = std::get<Sphere>(bodies[a].shape).radius;
  const Mat3 R = box.orientation.toRotationMatrix();
  const Vec3 p = R.transpose() * (bodies[a].position - box.position);  // centre in the box frame
  const Vec3 q = p.cwiseMax(-h).cwiseMin(h);
  Vec3 out_of_box;  // box frame, unit, from the box towards the sphere
  double distance;  // signed: centre outside (> 0) or inside (< 0) the box
  if ((p - q).squaredNorm() > 0) {
    distance = (p - q).norm();
    out_of_box = (p - q) / distance;
  } else {  // centre inside: leave through the nearest face
    Eigen::Index axis;
    (h - p.cwiseAbs()).minCoeff(&axis);
    distance = -(h[axis] - std::abs(p[axis]));
    out_of_box = Vec3::Zero();
    out_of_box[axis] = p[axis] >= 0 ? 1.0 : -1.0;
    const Vec3 face = p + out_of_box * (-distance);
    const Vec3 n = -(R * out_of_box);  // from the sphere into the box
    const double pen = r - distance;
    return make(bodies, a, b, box.position + R * face, n, pen);
  }
  const double pen = r - distance;
  const Vec3 n = -(R * out_of_box);
  return make(bodies, a, b, box.position + R * q + (R * out_of_box) * (0.5 * pen), n, pen);
}

// Vertex k of cuboid a against plane b.
RigidContact cuboid_plane(std::span<const RigidBody> bodies, std::size_t a, std::size_t b, std::size_t k) {
  const Plane& p = std::get<Plane>(bodies[b].shape);
  const Vec3 v = vertex(bodies[a], static_cast<int>(k));
  const double pen = p.offset - p.normal.dot(v);
  return make(bodies, a, b, v + p.normal * (0.5 * pen), -p.normal, pen);
}

}  // namespace

Vec3 vertex(const RigidBody& body, int i) {
  const Vec3 h = std::get<Cuboid>(body.shape).half_extents;
  const Vec3 corner((i & 1) ? h[0] : -h[0], (i & 2) ? h[1] : -h[1], (i & 4) ? h[2] : -h[2]);
  return body.position + body.orientation.toRotationMatrix() * corner;
}

std::vector<Vec3> vertices(const RigidBody& body) {
  std::vector<Vec3> out;
  for (int i = 0; i < 8; ++i) out.push_back(vertex(body, i));
  return out;
}

std::size_t candidate_count(const RigidBody& a, const RigidBody& b) {
  const auto is_sphere = [](const RigidBody& body) { return std::holds_alternative<Sphere>(body.shape); };
  const auto is_cuboid = [](const RigidBody& body) { return std::holds_alternative<Cuboid>(body.shape); };
  const auto is_plane = [](const RigidBody& body) { return std::holds_alternative<Plane>(body.shape); };
  if (is_sphere(a) || is_sphere(b)) return 1;  // against any shape: one closest point
  if ((is_cuboid(a) && is_plane(b)) || (is_plane(a) && is_cuboid(b))) return 8;  // one per vertex
  return 0;                                                                      // not needed
}

double overlap_extent(const RigidBody& a, const RigidBody& b) {
  const auto* sa = std::get_if<Sphere>(&a.shape);
  const auto* sb = std::get_if<Sphere>(&b.shape);
  const auto* ca = std::get_if<Cuboid>(&a.shape);
  const auto* cb = std::get_if<Cuboid>(&b.shape);
  if (sa && sb) return sa->radius + sb->radius;
  if (sa && cb) return sa->radius + cb->half_extents.minCoeff();
  if (ca && sb) return sb->radius + ca->half_extents.minCoeff();
  return std::numeric_limits<double>::infinity();
}

RigidContact contact_candidate(std::span<const RigidBody> bodies, std::size_t a, std::size_t b,
                               std::size_t k) {
  const Shape &A = bodies[a].shape, &B = bodies[b].shape;
  const bool as = std::holds_alternative<Sphere>(A), bs = std::holds_alternative<Sphere>(B);
  const bool ac = std::holds_alternative<Cuboid>(A), bc = std::holds_alternative<Cuboid>(B);
  const bool ap = std::holds_alternative<Plane>(A), bp = std::holds_alternative<Plane>(B);
  if (as && bs) return sphere_sphere(bodies, a, b);
  if (as && bp) return sphere_plane(bodies, a, b);
  if (ap && bs) return flip(bodies, sphere_plane(bodies, b, a));
  if (as && bc) return sphere_cuboid(bodies, a, b);
  if (ac && bs) return flip(bodies, sphere_cuboid(bodies, b, a));
  if (ac && bp) return cuboid_plane(bodies, a, b, k);
  if (ap && bc) return flip(bodies, cuboid_plane(bodies, b, a, k));
  throw std::invalid_argument("contact_candidate: no contact between these shapes");
}

std::vector<RigidContact> contact_candidates(std::span<const RigidBody> bodies, std::size_t a,
                                             std::size_t b) {
  std::vector<RigidContact> out;
  for (std::size_t k = 0; k < candidate_count(bodies[a], bodies[b]); ++k)
    out.push_back(contact_candidate(bodies, a, b, k));
  return out;
}

}  // namespace contact::rigid
