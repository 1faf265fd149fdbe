#include "contact_ode/models/scene_registry.hpp"

#include "contact_ode/models/registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace contact {

const std::vector<SceneEntry>& scene_registry() {
  static const std::vector<SceneEntry> all = [] {
    std::vector<SceneEntry> scenes = {ball_drop_scene(), ball_chain_scene(), spring_mass_scene(),
                                      ball_stack_scene()};
    for (auto& s : rigid_scene_entries()) scenes.push_back(std::move(s));
    return scenes;
  }();
  return all;
}

std::vector<std::string> scene_names() { return names_of(scene_registry()); }

const SceneEntry& scene_entry(const std::string& name) {
  return find_named(scene_registry(), name, "--scene");
}

std::unique_ptr<Dynamics> make_scene(const std::string& name, const ParameterValues& given,
                                     const std::string& law) {
  const SceneEntry& s = scene_entry(name);
  if (!law.empty() && !s.takes_law)
    throw std::invalid_argument(fmt::format("--law: scene '{}' fixes its own contact law", name));
  return s.make(resolve(s.parameters, given, name), law);
}

}  // namespace contact
