#include "contact_ode/models/spring_mass.hpp"

#include "contact_ode/models/scene_registry.hpp"

namespace contact {

SceneEntry spring_mass_scene() {
  return {"spring-mass",
          "a mass on a bilateral linear spring, no contact (the fixed-step schemes' closed forms)",
          {{"m", "kg", 1.0, "mass", kPositive},
           {"k", "N/m", 1e4, "spring stiffness", kPositive},
           {"x0", "m", 1.0, "initial displacement"},
           {"v0", "m/s", 0.0, "initial velocity"}},
          "",
          {"energy", "phase"},
          "x = x0 cos(w t) + (v0/w) sin(w t), w = sqrt(k/m); each fixed-step scheme's energy map",
          1.0,
          [](const ParameterValues& v, const std::string&) -> std::unique_ptr<Dynamics> {
            return std::make_unique<SpringMass>(v.at("m"), v.at("k"), v.at("x0"), v.at("v0"));
          }};
}

}  // namespace contact
