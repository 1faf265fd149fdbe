#pragma once
// Contact generation for the pairs the 3D scenes need, with a signed penetration so that the same
// candidates serve game detection (penetration > 0), penalty forces and root finding on the gap
// (-penetration) as bodies approach.
//   sphere-sphere    one candidate, along the line of centres
//   sphere-plane     one candidate, along the plane's normal
//   sphere-cuboid    one candidate, from the closest point of the (oriented) box to the centre:
//                    a face, an edge or a corner
//   cuboid-plane     eight candidates, one per vertex
// Convention (the tutorial's): the normal points from body a to body b; resolving moves a along
// -normal and b along +normal. The contact point is the middle of the overlap; lever arms are
// point - centre, and zero for bodies that do not rotate (axis-aligned boxes, static bodies).
#include "contact_ode/models/rigid/rigid_body.hpp"

#include <span>
#include <vector>

namespace contact::rigid {

struct RigidContact {
  std::size_t a = 0, b = 0;
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  double penetration = 0.0;  // > 0 overlapping, < 0 apart by that much
  Vec3 r_a = Vec3::Zero(), r_b = Vec3::Zero();
};

// How many candidates bodies a and b have: 1 for a pair with a sphere, 8 for cuboid-plane, 0 for
// pairs no scene needs (cuboid-cuboid, plane-plane).
std::size_t candidate_count(const RigidBody& a, const RigidBody& b);
// The overlap at which a's and b's contact normal turns about [m]: two spheres' centres cross at
// ra + rb, a sphere's centre reaches a cuboid's middle at r plus its smallest half extent (or
// sooner, its nearest face changing); a plane's never does (inf).
double overlap_extent(const RigidBody& a, const RigidBody& b);

// Candidate k < candidate_count of bodies a and b (indices into `bodies`): what one contact's
// queries need, without computing the pair's others.
RigidContact contact_candidate(std::span<const RigidBody> bodies, std::size_t a, std::size_t b,
                               std::size_t k);

// Every candidate between bodies a and b; empty for pairs no scene needs.
std::vector<RigidContact> contact_candidates(std::span<const RigidBody> bodies, std::size_t a, std::size_t b);

// World position of a cuboid's vertex i in [0, 8) (bit j of i: the + side along axis j), and all eight.
Vec3 vertex(const RigidBody& cuboid, int i);
std::vector<Vec3> vertices(const RigidBody& cuboid);

}  // namespace contact::rigid
