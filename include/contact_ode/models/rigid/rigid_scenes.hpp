#pragma once
// The named rigid-body scenes, one registry shared by tests, experiments and benchmarks.
//   snooker        cue ball into a resting red ball of equal mass (e = 1: they exchange speeds)
//   planet         cue ball into a "planet" 10^6 times heavier (it must not move)
//   spinning-box   a box spinning in place sweeps its corner into a resting sphere
//   off-centre     a sphere hits a resting cuboid off its centre line (the cuboid twists)
//   rubber-steel   a rubber (0.9) and a steel (0.4) ball dropped on the floor (e = product of
//                  elasticities; the floor's is the elasticity parameter, 1 by default)
//   cradle         Newton's cradle: a striker into four touching balls
//   wedge          a striker meets two balls at once (the sequential rule's order-dependence)
// Parameters: the balls' mass and radius, the cue ball's, striker's or lone sphere's elasticity,
// the cuboid's half extents and orientation, and the penalty stiffness (Kelvin–Voigt damping tuned
// to the scene's nominal e).
#include "contact_ode/models/rigid/rigid_scene.hpp"

#include <functional>
#include <string>
#include <vector>

namespace contact::rigid {

struct SceneParams {
  double m = 0.17;        // mass of each ball [kg] (planet: the cue ball's)
  double radius = 0.026;  // radius of each ball [m] (planet: the cue ball's)
  // The cue ball's, striker's or lone sphere's (cradle: every ball's; rubber-steel: the floor's).
  double elasticity = 1.0;
  Vec3 half_extents = Vec3(0.3, 0.2, 0.1);  // the cuboid's [m]
  Quat orientation = Quat::Identity();      // the cuboid's initial orientation
  double k = 1e6;                           // penalty stiffness [N/m]
};

struct SceneInfo {
  std::string name;
  std::string description;
  double t_end;  // [s]
  std::function<RigidScene(const SceneParams&)> make;
};

const std::vector<SceneInfo>& rigid_scene_registry();
std::vector<std::string> rigid_scene_names();
// Throws std::invalid_argument naming the accepted scenes.
const SceneInfo& rigid_scene(const std::string& name);

}  // namespace contact::rigid
