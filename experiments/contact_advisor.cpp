// contact_advisor — what contact parameters and step to use, and what they cost.
// Given a mass, an impact speed, a target restitution and a maximum penetration or a contact
// duration (or, for Hertz, a material), prints the contact law's parameters, the contact
// frequency, the largest stable explicit and semi-implicit Euler steps, the semi-implicit step for
// an energy error per contact, the same contact as ODE/Bullet ERP and CFM, MuJoCo solref, Box2D
// soft contact and Drake's penetration allowance, and checks the answer by simulating the contact.
// Derivations: analysis/contact_advisor.hpp and models/engine_conventions.hpp.
// Outputs in --out (default results/contact_advisor): advice.{csv,md,tex}, meta.json.
// Exit codes: 0 success, 1 the check's simulation failed, 2 bad input.
#include "contact_ode/analysis/contact_advisor.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/models/law_registry.hpp"
#include "experiment.hpp"
#include "output.hpp"
#include "process.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <iostream>

using namespace contact;

int program(int argc, char** argv) {
  ContactRequest r;
  double max_penetration = 0, duration = 0, radius = 0, young = 0, poisson = 0;
  std::string rule{to_string(kDefaultDampingRule)};
  Experiment app("contact_advisor",
                 "Contact parameters and steps for a required penetration or duration and restitution, "
                 "in this project's laws and in popular engines' conventions.",
                 "results/contact_advisor");
  app.add("--m", r.m, "effective mass of the contact [kg]", cli::positive());
  app.add("--v", r.v, "impact speed [m/s]", cli::positive());
  app.add("--e", r.e, "target coefficient of restitution", cli::real_in(0, 1, false, false));
  app.add_unset("--max-penetration", max_penetration, "required maximum penetration [m] (or --duration)",
                cli::positive());
  app.add_unset("--duration", duration, "required contact duration [s] (or --max-penetration)",
                cli::positive());
  app.add("--law", r.law, "contact law", cli::one_of(law_names()));
  app.add("--rule", rule, "damping rule of the Hunt-Crossley laws (hertz, hunt-crossley-linear)",
          cli::one_of(damping_rule_names()));
  app.add_unset("--radius", radius, "hertz from a material: sphere radius [m]", cli::positive());
  app.add_unset("--young", young, "hertz from a material: Young's modulus [Pa]", cli::positive());
  app.add_unset("--poisson", poisson, "hertz from a material: Poisson ratio",
                cli::real_in(-1, 0.5, true, true));
  app.add("--energy-error", r.energy_error, "energy error per contact the game step may cost",
          cli::real_in(0, 1, true, true));
  app.add("--engine-step", r.engine_step, "engine time step for ERP and CFM [s]", cli::positive());
  app.add("--g", r.g, "gravity for Drake's penetration allowance [m/s^2]", cli::positive());
  return app.run(argc, argv, [&](OutputSet& files) {
    if (app.given("--max-penetration")) r.max_penetration = max_penetration;
    if (app.given("--duration")) r.duration = duration;
    if (app.given("--radius")) r.radius = radius;
    if (app.given("--young")) r.young = young;
    if (app.given("--poisson")) r.poisson = poisson;
    if (app.given("--rule")) r.rule = parse_damping_rule(rule);
    validate(r);
    const ContactAdvice a = advise(r);
    const double nan = std::nan("");
    Table t({"quantity", "value", "unit", "note"});
    auto row = [&](const std::string& q, double v, const std::string& unit, const std::string& note = "") {
      t.add_row({q, v, unit, note});
    };
    t.add_row({"law", nan, "", describe(a.law)});
    row("k_lin", a.k_lin, "N/m", "stiffness, linearised at the maximum penetration");
    row("c_lin", a.c_lin, "N s/m", "damping, linearised at the maximum penetration");
    row("omega", a.omega, "rad/s", "contact frequency sqrt(k/m)");
    row("frequency", a.frequency_hz, "Hz", "");
    row("zeta", a.zeta, "", "damping ratio");
    row("euler_max_dt", a.euler_max_dt, "s", "largest stable explicit Euler step (0: none)");
    row("symplectic_max_dt", a.symplectic_max_dt, "s", "largest stable semi-implicit Euler step");
    row("game_dt", a.game_dt, "s",
        fmt::format("semi-implicit Euler step for an energy error of {:g} per contact", r.energy_error));
    row("ode_erp", a.ode.erp, "", fmt::format("ODE/Bullet at step {:g} s", r.engine_step));
    row("ode_cfm", a.ode.cfm, "m/(N s)", fmt::format("ODE/Bullet at step {:g} s", r.engine_step));
    // solref = (timeconst, dampratio) puts k = 1 / (timeconst dampratio)^2 and b = 2 / timeconst: an
    // undamped contact is their limit, timeconst -> inf at dampratio 0, which no model can be given.
    row("mujoco_timeconst", a.mujoco.timeconst, "s",
        std::isinf(a.mujoco.timeconst)
            ? "solref[0]: none for an undamped contact; use solref = (-stiffness, 0)"
            : "solref[0], impedance 1");
    row("mujoco_dampratio", a.mujoco.dampratio, "", "solref[1]");
    row("mujoco_stiffness", a.mujoco_direct.stiffness, "1/s^2", "solref = (-stiffness, -damping)");
    row("mujoco_damping", a.mujoco_direct.damping, "1/s", "");
    row("box2d_hertz", a.box2d.hertz, "Hz", "contact hertz");
    row("box2d_damping_ratio", a.box2d.damping_ratio, "", "");
    row("drake_penetration_allowance", a.drake.penetration_allowance, "m",
        fmt::format("at g = {:g} m/s^2", r.g));
    row("drake_dissipation", a.drake.dissipation, "s/m", "Hunt-Crossley d Drake derives from it");
    row("requested_penetration", r.max_penetration.value_or(nan), "m", "");
    row("achieved_penetration", a.achieved_penetration, "m", "simulated");
    row("requested_duration", r.duration.value_or(nan), "s", "");
    row("achieved_duration", a.achieved_duration, "s", "simulated");
    row("requested_restitution", r.e, "", "");
    row("achieved_restitution", a.achieved_restitution, "", "simulated");
    row("game_energy_error", a.game_energy_error, "",
        "simulated after one contact at game_dt, worst of 32 entry phases");
    fmt::print("Contact advice: m = {:g} kg, v = {:g} m/s, e = {:g}, law {}\n\n{}", r.m, r.v, r.e, r.law,
               t.to_markdown(6));
    files.add_table("advice", t);
  });
}

int main(int argc, char** argv) { return contact::guarded_main("contact_advisor", argc, argv, program); }
