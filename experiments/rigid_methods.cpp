#include "rigid_methods.hpp"

#include "event_driven.hpp"
#include "game_step.hpp"
#include "penalty.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace contact {

std::vector<std::string> rigid_method_names() { return {"penalty", "game", "game-projection", "event", "event-reversed"}; }

RunResult run_rigid(const rigid::RigidScene& scene, const std::string& method, const RigidRunSettings& s) {
  IntegratorOptions integrator;
  integrator.rtol = s.rtol;
  integrator.atol = s.atol;
  RunResult r;
  if (method == "penalty") {
    r = run_penalty(scene, PenaltyOptions{s.t_end, s.sample_dt, integrator, true});
  } else if (method == "game" || method == "game-projection") {
    r = run_game(scene, {s.dt, s.t_end, s.sample_dt, FixedStepScheme::SemiImplicitEuler,
                         method == "game" ? GameResolution::ProjectionImpulse : GameResolution::Projection});
  } else if (method == "event" || method == "event-reversed") {
    EventOptions o;
    o.t_end = s.t_end;
    o.sample_dt = s.sample_dt;
    o.integrator = integrator;
    o.reverse_order = method == "event-reversed";
    r = run_event_driven(scene, o);
  } else {
    throw std::invalid_argument(fmt::format("unknown rigid method '{}'", method));
  }
  r.method = method;
  return r;
}

}  // namespace contact
