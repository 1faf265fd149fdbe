#pragma once
// The capabilities a paradigm asks of a scene (models/mechanical_system.hpp): every scene has
// dynamics; contact geometry and an impulse map are found by type. A scene without contacts gets
// an empty geometry, so a paradigm runs it as a plain ODE; a paradigm that needs an impulse map
// and meets a scene without one refuses it by name.
#include "contact_ode/models/mechanical_system.hpp"

#include <string_view>

namespace contact {

// The scene's contact geometry, or an empty one (no contacts) for a scene that has none; throws
// std::invalid_argument for a scene that has contacts but no geometry.
const ContactGeometry& contact_geometry(const Dynamics& scene);
// Whether the scene offers projection and impulses.
bool has_impulse_map(const Dynamics& scene);
// Its impulse map; throws std::invalid_argument naming `method` and the scene when it has none.
const ImpulseMap& impulse_map(const Dynamics& scene, std::string_view method);
// Whether the scene offers normal impulses of any size (time-stepping solvers).
bool has_normal_impulses(const Dynamics& scene);
// Whether it offers normal impulses and every contact's penalty law is linear (a spring to match:
// XPBD's compliance, an engine's spring setting).
bool has_linear_laws(const Dynamics& scene);
// Its normal impulses; throws std::invalid_argument naming `method` and the scene when it has none.
const NormalImpulses& normal_impulses(const Dynamics& scene, std::string_view method);

}  // namespace contact
