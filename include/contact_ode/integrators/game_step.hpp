#pragma once
// Game-style integration: a fixed step dt made of named stages, as the seed's physics loop does.
//   1. integrate   one explicit or semi-implicit Euler step (free flight, or with the penalty
//                  spring force while a contact's switching function is positive);
//   2. detect      every contact with gap < 0 (or, for the spring, a positive switching value);
//   3. resolve     projection by inverse-mass share, then the impulse if still approaching
//                  (the seed's ImpulseResolveCollision), or nothing for the spring;
//   4. notify      contact begin/end are decided after the step, in one batch.
//
// Gameplay notifications follow the tutorial's collision list (integrators/collision_list.hpp):
// Begin when a pair is first detected, End `persistence` frames after its last detection, in one
// batch after each step, a callback, if given, invoked only from that batch.
//
// The impulse is applied only when the contact approaches (gap rate < 0). The seed applies it
// unconditionally; on a separating contact that would pull the bodies back together.
//
// A contact record spans the frames in which the contact is detected: it ends when a resolution
// leaves the bodies apart and separating, and is reopened if the very next frame detects the
// contact again. A ball resting on the floor, detected and resolved every frame, is thus one
// record, not one per frame.
//
// Contact times are the linear interpolation of the detection function's zero between two step
// ends, so they carry an O(dt) error by construction; apexes are located where the gap rate,
// interpolated linearly between step ends, falls through zero.
#include "contact_ode/integrators/fixed_step.hpp"
#include "contact_ode/integrators/run_recorder.hpp"
#include "contact_ode/integrators/run_result.hpp"
#include "contact_ode/models/mechanical_system.hpp"

#include <functional>

namespace contact {

enum class GameResolution {
  ProjectionImpulse,  // the seed's combination
  Projection,         // position correction only
  Impulse,            // velocity change only
  Spring,             // penalty force from the contact law ("ResolveSpringCollision")
};

std::string_view to_string(GameResolution r);

struct GameOptions {
  double dt = 1e-3;  // fixed step [s]
  FixedStepScheme scheme = FixedStepScheme::SemiImplicitEuler;
  GameResolution resolution = GameResolution::ProjectionImpulse;
  int persistence = 1;  // frames a pair stays listed after its last detection
  std::function<void(const std::vector<CollisionEvent>&)> on_notifications;  // once per step with events
};

// Projection and impulses need the scene's impulse map (std::invalid_argument without one).
RunResult run_game(const Dynamics& model, const GameOptions& options, const SolveOptions& span = {});

}  // namespace contact
