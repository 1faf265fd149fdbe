#pragma once
// The named rigid-body scenes, one registry shared by tests, experiments and benchmarks.
//   snooker        cue ball into a resting red ball of equal mass (e = 1: they exchange speeds)
//   planet         cue ball into a "planet" 10^6 times heavier (it must not move)
//   spinning-box   a box spinning in place sweeps its corner into a resting sphere
//   off-centre     a sphere hits a resting cuboid off its centre line (the cuboid twists)
//   rubber-steel   a rubber and a steel ball dropped on the floor (e = product of elasticities)
//   cradle         Newton's cradle: a striker into four touching balls
//   wedge          a striker meets two balls at once (the sequential rule's order-dependence)
// Parameters: the moving ball's mass, radius and elasticity, the cuboid's half extents and
// orientation, and the penalty stiffness (Kelvin–Voigt damping tuned to the scene's nominal e).
#include "contact_ode/models/rigid/rigid_scene.hpp"

#include <functional>
#include <string>
#include <vector>

namespace contact::rigid {

struct SceneParams {
  double m = 0.17;                          // mass of the moving ball [kg]
  double radius = 0.026;                    // its radius [m]
  double elasticity = 1.0;                  // its elasticity
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
