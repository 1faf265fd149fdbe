#include "contact_ode/models/rigid/rigid_scenes.hpp"

#include "contact_ode/models/registry.hpp"

#include "contact_ode/models/scene_registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace contact::rigid {

namespace {

constexpr double kGap = 1e-3;  // initial clearance of the moving body [m]

// Each pair's spring: stiffness k, Kelvin–Voigt damping tuned to the pair's restitution and
// effective mass.
RigidScene::LawForPair law_for(const SceneParams& p) {
  return [k = p.k](double e, double m_eff) {
    return ContactLaw{kelvin_voigt_for_restitution(k, m_eff, e, false)};
  };
}

RigidScene snooker(const SceneParams& p, double other_mass, double other_radius) {
  RigidBody cue = RigidBody::sphere("cue", p.m, p.radius, p.elasticity);
  RigidBody red = RigidBody::sphere("red", other_mass, other_radius, 1.0);
  cue.velocity = Vec3(2.0, 0, 0);
  red.position = Vec3(p.radius + other_radius + kGap, 0, 0);
  return RigidScene("snooker", {cue, red}, Vec3::Zero(), law_for(p));
}

RigidScene spinning_box(const SceneParams& p) {
  RigidBody box = RigidBody::cuboid("box", 1.0, p.half_extents, 1.0);
  box.orientation = p.orientation;
  box.angular_velocity = box.orientation * Vec3(0, 0, 4);  // about the box's own z axis
  // The sphere waits on the circle the box's vertical edge at (+x, +y) sweeps, ahead of it by
  // the smallest angle that clears the box by kGap: the edge then strikes it.
  const Vec3 edge(p.half_extents.x(), p.half_extents.y(), 0);
  RigidBody ball = RigidBody::sphere("ball", p.m, p.radius, p.elasticity);
  for (double phi = 0.0; phi < 3.0; phi += 1e-3) {
    ball.position = box.position + box.orientation * (Quat(Eigen::AngleAxisd(phi, Vec3::UnitZ())) * edge);
    std::vector<RigidBody> pair{box, ball};
    if (contact_candidates(pair, 0, 1)[0].penetration <= -kGap) break;
  }
  return RigidScene("spinning-box", {box, ball}, Vec3::Zero(), law_for(p));
}

RigidScene off_centre(const SceneParams& p) {
  RigidBody box = RigidBody::cuboid("box", 1.0, p.half_extents, 1.0);
  box.orientation = p.orientation;
  RigidBody ball = RigidBody::sphere("ball", p.m, p.radius, p.elasticity);
  const Mat3 R = p.orientation.toRotationMatrix();
  ball.position = R * Vec3(p.half_extents.x() + p.radius + kGap, 0.6 * p.half_extents.y(), 0);
  ball.velocity = -2.0 * (R * Vec3::UnitX());
  return RigidScene("off-centre", {ball, box}, Vec3::Zero(), law_for(p));
}

// The balls' elasticities are the scene (0.9 and 0.4); the parameter is the floor's, which
// scales both restitutions (it was ignored, a silent no-op).
RigidScene rubber_steel(const SceneParams& p) {
  RigidBody rubber = RigidBody::sphere("rubber", p.m, p.radius, 0.9),
            steel = RigidBody::sphere("steel", p.m, p.radius, 0.4);
  rubber.position = Vec3(0, 0, 1.0);
  steel.position = Vec3(1.0, 0, 1.0);
  return RigidScene("rubber-steel",
                    {rubber, steel, RigidBody::plane("floor", Vec3::UnitZ(), 0.0, p.elasticity)},
                    Vec3(0, 0, -9.81), law_for(p));
}

RigidScene cradle(const SceneParams& p) {
  std::vector<RigidBody> balls;
  for (int i = 0; i < 5; ++i) {
    RigidBody b = RigidBody::sphere(fmt::format("ball{}", i), p.m, p.radius, p.elasticity);
    b.position = Vec3(2 * p.radius * i + (i > 0 ? kGap : 0.0), 0, 0);
    balls.push_back(b);
  }
  balls[0].velocity = Vec3(1.0, 0, 0);
  return RigidScene("cradle", balls, Vec3::Zero(), law_for(p));
}

// The striker reaches two balls at +-30 degrees off its path at the same instant: simultaneous
// contacts, which the sequential impulse rule resolves one after the other.
RigidScene wedge(const SceneParams& p) {
  RigidBody striker = RigidBody::sphere("striker", p.m, p.radius, p.elasticity);
  striker.velocity = Vec3(1.0, 0, 0);
  const double d = 2 * p.radius + kGap, c = std::sqrt(3.0) / 2;
  RigidBody upper = RigidBody::sphere("upper", p.m, p.radius, 1.0),
            lower = RigidBody::sphere("lower", p.m, p.radius, 1.0);
  upper.position = Vec3(d * c, d * 0.5, 0);
  lower.position = Vec3(d * c, -d * 0.5, 0);
  return RigidScene("wedge", {striker, upper, lower}, Vec3::Zero(), law_for(p));
}

// A body refuses numbers it cannot hold, naming its own quantity (a radius of 1e-300 m gave the
// cue ball an inverse inertia of inf, refused as 'cue inverse inertia'): the refusal names the
// scene's sizes and masses as well.
std::vector<SceneInfo> naming_parameters(std::vector<SceneInfo> scenes) {
  for (SceneInfo& info : scenes) {
    info.make = [name = info.name, make = info.make](const SceneParams& p) {
      try {
        return make(p);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(fmt::format(
            "scene '{}' cannot be made of m '{}', radius '{}' and half extents '{} {} {}' ({}); accepted: "
            "masses and sizes whose inertias and inverse inertias are finite and positive doubles",
            name, p.m, p.radius, p.half_extents.x(), p.half_extents.y(), p.half_extents.z(), e.what()));
      }
    };
  }
  return scenes;
}

}  // namespace

const std::vector<SceneInfo>& rigid_scene_registry() {
  static const std::vector<SceneInfo> scenes = naming_parameters({
      {"snooker", "cue ball into a resting red ball of equal mass", 0.05,
       [](const SceneParams& p) { return snooker(p, p.m, p.radius); }},
      {"planet", "cue ball into a planet 1e6 times heavier", 0.05,
       [](const SceneParams& p) { return snooker(p, p.m * 1e6, p.radius * 100); }},
      {"spinning-box", "a spinning box's corner knocks a resting sphere", 0.05, spinning_box},
      {"off-centre", "a sphere hits a resting cuboid off its centre line", 0.05, off_centre},
      {"rubber-steel", "a rubber (0.9) and a steel (0.4) ball dropped on the floor", 1.5, rubber_steel},
      {"cradle", "Newton's cradle: a striker into four touching balls", 0.05, cradle},
      {"wedge", "a striker meets two balls at once, symmetric about its path (order-dependence)", 0.05,
       wedge},
  });
  return scenes;
}

std::vector<std::string> rigid_scene_names() { return names_of(rigid_scene_registry()); }

const SceneInfo& rigid_scene(const std::string& name) {
  return find_named(rigid_scene_registry(), name, "--scene");
}

}  // namespace contact::rigid

namespace contact {

std::vector<SceneEntry> rigid_scene_entries() {
  const rigid::SceneParams d;
  std::vector<SceneEntry> entries;
  for (const auto& info : rigid::rigid_scene_registry()) {
    entries.push_back(
        {info.name,
         info.description,
         {{"m", "kg", d.m, "mass of each ball (planet: the cue ball's, the planet's 1e6 times it)",
           kPositive},
          {"radius", "m", d.radius, "radius of each ball (planet: the cue ball's, the planet's 100 times it)",
           kPositive},
          {"elasticity", "", d.elasticity,
           "elasticity of the cue ball, striker or lone sphere (cradle: every ball's; rubber-steel: the "
           "floor's, the balls' being 0.9 and 0.4; the other bodies' 1); restitution: the product of the "
           "pair's",
           kUnitInterval},
          {"k", "N/m", d.k, "penalty stiffness (Kelvin-Voigt, damping tuned to each pair's e)", kPositive}},
         "",  // each pair's Kelvin–Voigt law, tuned to its restitution
         {"velocities", "momentum", "angular momentum", "energy", "contact log"},
         "",
         info.t_end,
         [make = info.make](const ParameterValues& v, const std::string&) -> std::unique_ptr<Dynamics> {
           rigid::SceneParams p;
           p.m = v.at("m");
           p.radius = v.at("radius");
           p.elasticity = v.at("elasticity");
           p.k = v.at("k");
           return std::make_unique<rigid::RigidScene>(make(p));
         }});
  }
  return entries;
}

}  // namespace contact
