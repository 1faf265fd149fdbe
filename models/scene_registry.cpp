#include "contact_ode/models/scene_registry.hpp"

#include "contact_ode/models/mechanical_system.hpp"
#include "contact_ode/models/memory_limit.hpp"
#include "contact_ode/models/registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
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
  if (!law.empty() && s.default_law.empty())
    throw std::invalid_argument(fmt::format("--law: scene '{}' fixes its own contact law", name));
  auto scene = s.make(resolve(s.parameters, given, name), law.empty() ? s.default_law : law);
  std::string settings;
  for (const auto& [parameter, value] : given)
    settings += fmt::format("{}{} = {:g}", settings.empty() ? "" : ", ", parameter, value);
  const std::string at = settings.empty() ? "its defaults" : settings;
  require_state_fits(*scene, at);
  require_bodies_apart(*scene, at);
  return scene;
}

void require_state_fits(const Dynamics& scene, const std::string& settings) {
  // Before the first state is built (the gaps below are checked on one): a chain of 5e8 balls
  // allocated its 8 GB here, and ended in std::bad_alloc, or the OOM killer, before solve() could
  // refuse the run for the memory it needs. A run holds at least this state, so the bound is solve()'s.
  const double values = static_cast<double>(scene.state_size());
  const double bytes = sizeof(double) * values, held = half_the_memory_limit();
  if (bytes > held)
    throw std::invalid_argument(fmt::format(
        "scene '{}' at {}: its state alone is {:.3g} values ({:.3g} GB); a run may hold {:.3g} GB (half the "
        "memory this process may use): fewer bodies",
        scene.name(), settings, values, bytes / 1e9, held / 1e9));
}

void require_bodies_apart(const Dynamics& scene, const std::string& settings) {
  const auto* geometry = dynamic_cast<const ContactGeometry*>(&scene);
  if (geometry == nullptr) return;
  const Vector y0 = scene.initial_state();
  // Touching: a gap of 1e-12 of the positions' size (at least 1 m) or less, far above the few ulps
  // of rounding a touching pair's gap has and far below an overlap any method would notice.
  const double positions = y0.size() > 0 ? scene.position_mask().select(y0.cwiseAbs(), 0.0).maxCoeff() : 0.0;
  const double touching = 1e-12 * std::max(1.0, positions);
  for (std::size_t i = 0; i < scene.contact_count(); ++i) {
    const double gap = geometry->gap(i, y0);
    // A gap that is not finite means sizes the geometry cannot hold: squared distances past 1.8e308
    // (a wedge of balls of radius 1e300 m) gave gaps of inf, and the game methods ran the striker
    // through both balls without a contact, answering 'success'.
    if (!std::isfinite(gap))
      throw std::invalid_argument(fmt::format(
          "scene '{}' at {}: contact {} starts with a gap of {} m, which the geometry cannot compute at "
          "these sizes; accepted: sizes and positions whose squares are finite doubles (below 1e154 m)",
          scene.name(), settings, i, gap));
    if (gap < -touching)
      throw std::invalid_argument(fmt::format(
          "scene '{}' at {}: contact {} starts with its bodies {:.3g} m inside each other; bodies must start "
          "apart or touching",
          scene.name(), settings, i, -gap));
  }
}

}  // namespace contact
