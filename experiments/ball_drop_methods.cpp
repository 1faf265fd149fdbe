#include "ball_drop_methods.hpp"

#include "event_driven.hpp"
#include "game_step.hpp"
#include "penalty.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace contact {

const std::vector<MethodInfo>& ball_drop_methods() {
  static const std::vector<MethodInfo> methods = {
      {"penalty", "penalty spring as an ODE (--integrator, CVODE BDF by default), analytic Jacobian, switches root-located", true},
      {"penalty-dq", "as penalty, with the integrator's difference-quotient Jacobian", true},
      {"game-euler", "explicit Euler at fixed dt, projection + impulse", false},
      {"game-symplectic", "semi-implicit Euler at fixed dt, projection + impulse", false},
      {"game-euler-spring", "explicit Euler at fixed dt, penalty spring force", true},
      {"game-symplectic-spring", "semi-implicit Euler at fixed dt, penalty spring force", true},
      {"event-ode", "event-driven impulses, flight integrated with root finding (--integrator)", false},
      {"event-exact", "event-driven impulses, exact parabolic flight (reference)", false},
  };
  return methods;
}

std::vector<std::string> ball_drop_method_names() {
  std::vector<std::string> names;
  for (const auto& m : ball_drop_methods()) names.push_back(m.name);
  return names;
}

std::vector<std::string> law_names() { return {"hooke", "kelvin-voigt", "kelvin-voigt-clamped"}; }

ContactLaw make_law(const std::string& name, double k, double m, double e) {
  if (name == "hooke") return Hooke{k};
  if (name == "kelvin-voigt") return kelvin_voigt_for_restitution(k, m, e, false);
  if (name == "kelvin-voigt-clamped") return kelvin_voigt_for_restitution(k, m, e, true);
  throw std::invalid_argument(fmt::format("unknown contact law '{}'", name));
}

RunResult run_ball_drop(const std::string& method, const BallDropSettings& s) {
  const BallDrop model(s.model);
  auto game = [&](FixedStepScheme scheme, GameResolution resolution) {
    return run_game(model, GameOptions{.dt = s.dt, .t_end = s.t_end, .sample_dt = s.sample_dt, .scheme = scheme, .resolution = resolution, .limits = s.limits});
  };
  auto events = [&] { return EventOptions{.t_end = s.t_end, .sample_dt = s.sample_dt, .integrator = s.integrator, .rest_speed = s.rest_speed, .max_events = s.max_events, .limits = s.limits}; };
  RunResult r;
  if (method == "penalty" || method == "penalty-dq") {
    PenaltyOptions o{.t_end = s.t_end, .sample_dt = s.sample_dt, .integrator = s.integrator, .limits = s.limits};
    if (method == "penalty-dq") o.integrator.jacobian = JacobianMode::DifferenceQuotient;
    r = run_penalty(model, o);
  } else if (method == "game-euler") {
    r = game(FixedStepScheme::ExplicitEuler, GameResolution::ProjectionImpulse);
  } else if (method == "game-symplectic") {
    r = game(FixedStepScheme::SemiImplicitEuler, GameResolution::ProjectionImpulse);
  } else if (method == "game-euler-spring") {
    r = game(FixedStepScheme::ExplicitEuler, GameResolution::Spring);
  } else if (method == "game-symplectic-spring") {
    r = game(FixedStepScheme::SemiImplicitEuler, GameResolution::Spring);
  } else if (method == "event-ode") {
    r = run_event_driven(model, events());
  } else if (method == "event-exact") {
    r = run_event_driven(model, model, events());
  } else {
    throw std::invalid_argument(fmt::format("unknown method '{}'", method));
  }
  r.method = method;
  return r;
}

}  // namespace contact
