#pragma once
// The numbers each rigid scene is about (speeds after impact, spins, apex ratios), read off a
// run of it: what rigid_scenes tabulates and the paper quotes, whatever method ran the scene.
#include "contact_ode/integrators/run_result.hpp"
#include "contact_ode/models/rigid/rigid_scene.hpp"

#include <string>
#include <utility>
#include <vector>

namespace contact::rigid {

using Observables = std::vector<std::pair<std::string, double>>;

// The observables of the scene registered as `scene` (empty for a scene without any).
Observables observe(const std::string& scene, const RigidScene& s, const RunResult& r);

}  // namespace contact::rigid
