#pragma once
// Every scene by name: one registry for the 1-D scenes and the rigid-body ones, shared by
// experiments, tests, benchmarks and the Python module. A new scene is one file defining its
// model and its entry, and one line in scene_registry.cpp.
#include "contact_ode/models/mechanical_system.hpp"
#include "contact_ode/models/parameters.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace contact {

struct SceneEntry {
  std::string name;
  std::string description;
  std::vector<ParameterInfo> parameters;
  // The law its contacts use unless the caller names another (law_registry.hpp); "": the scene
  // fixes its own and takes none.
  std::string default_law;
  std::vector<std::string> observables;  // what the study reads off it
  std::string exact;                     // the exact solutions known for it, in words ("" none)
  double t_end;                          // a span that shows its behaviour [s]
  std::function<std::unique_ptr<Dynamics>(const ParameterValues& values, const std::string& law)> make;
};

const std::vector<SceneEntry>& scene_registry();
std::vector<std::string> scene_names();
// Throws std::invalid_argument naming the accepted scenes.
const SceneEntry& scene_entry(const std::string& name);
// The scene with the given parameters (the others at their defaults) and, for a scene that takes
// one, the named law (empty: its default_law). Throws std::invalid_argument for an unknown
// scene, parameter or law, a state too large to hold, or bodies that start inside each other.
std::unique_ptr<Dynamics> make_scene(const std::string& name, const ParameterValues& given = {},
                                     const std::string& law = "");

// Throws std::invalid_argument, naming `settings` (the parameters that placed the bodies), when
// two of the scene's bodies start inside each other: every method then answers a different
// question (a penalty spring launches the ball out at hundreds of m/s; impulses refuse), so the
// scene is refused, as make_scene does. Touching (a gap of zero to rounding) is apart.
void require_bodies_apart(const Dynamics& scene, const std::string& settings);
// Throws std::invalid_argument, naming `settings`, when the scene's state alone is more than a run
// may hold (half_the_memory_limit()), before anything builds it; make_scene does this first.
void require_state_fits(const Dynamics& scene, const std::string& settings);

// The entries, each defined beside its model.
SceneEntry ball_drop_scene();
SceneEntry ball_chain_scene();
SceneEntry spring_mass_scene();
SceneEntry ball_stack_scene();
std::vector<SceneEntry> rigid_scene_entries();

}  // namespace contact
