#include "rigid_methods.hpp"

#include "event_driven.hpp"
#include "game_step.hpp"
#include "penalty.hpp"
#include "sweep_setting.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace contact {

std::vector<std::string> rigid_method_names() { return {"penalty", "game", "game-projection", "event", "event-reversed"}; }

bool is_fixed_step(const std::string& rigid_method) { return rigid_method.rfind("game", 0) == 0; }

RigidRunSettings with_setting(RigidRunSettings s, const std::string& rigid_method, double value) {
  if (is_fixed_step(rigid_method)) {
    s.dt = value;
  } else {
    s.rtol = value;
    s.atol = value * kAtolPerRtol;
  }
  return s;
}

RunResult run_rigid(const rigid::RigidScene& scene, const std::string& method, const RigidRunSettings& s) {
  IntegratorOptions integrator;
  integrator.rtol = s.rtol;
  integrator.atol = s.atol;
  RunResult r;
  if (method == "penalty") {
    r = run_penalty(scene, PenaltyOptions{.t_end = s.t_end, .sample_dt = s.sample_dt, .integrator = integrator});
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
