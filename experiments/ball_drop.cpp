// ball_drop — a ball dropped on a rigid floor, its contact resolved three ways:
//   penalty   the contact is a spring (Hooke or Kelvin–Voigt) and the whole motion one stiff ODE
//             under CVODE (BDF, Newton, dense, analytic or difference-quotient Jacobian), contact
//             begin/end located by root finding;
//   game      fixed-step explicit or semi-implicit Euler with the seed's projection + impulse,
//             or with the penalty spring force added to the acceleration;
//   event     free flight (CVODE with root finding, or the exact parabola), Newton's law
//             v+ = -e v- at each impact, Zeno cascade stopped by a rest guard.
// Model (models/ball_drop.hpp): x' = v, v' = -g (+ F(delta, delta_dot)/m in contact), delta = -x.
// Defaults: m = 1 kg, g = 9.81 m/s^2, h0 = 1 m, e = 0.8, k = 1e5 N/m, Kelvin–Voigt law tuned to e,
// t in [0, 3] s, dt = 1 ms, rtol = 1e-8, atol = 1e-10.
// Outputs in --out (default results/ball_drop): comparison.{csv,md,tex}, contacts.csv,
// apexes.csv, samples.csv, stats.csv, heights.{png,pdf,gp}, meta.json; with --sweep,
// sweep.{csv,md,tex}, penetration.{png,pdf,gp} (first penetration against k) and meta.json; under mpirun the
// sweep's runs go over the ranks. Exit codes: 0 success, 1 solver failure (status, time reached and message
// on stderr), 2 bad input.
#include "ball_drop_setup.hpp"
#include "contact_ode/analysis/run_tables.hpp"
#include "contact_ode/models/law_registry.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "process.hpp"
#include "progress.hpp"

#include <fmt/format.h>

#include <cmath>

namespace contact {

void run_single(const BallDropOptions& o, OutputSet& out) {
  std::vector<std::string> columns{"method"};
  columns.insert(columns.end(), metric_columns().begin(), metric_columns().end());
  Table comparison(columns);
  RunRecords records({"y_m", "v_mps"});
  const auto methods = chosen_methods(o);
  Progress progress("ball_drop", methods.size());
  std::size_t failures = 0;
  Series heights;
  for (const auto& name : methods) {
    progress.step(name);
    const RunResult r = run_ball(o, name, o.k, progress.follow(o.t_end));
    std::string rows;
    for (const auto& smp : r.samples) rows += fmt::format("{},{}\n", smp.t, smp.y[0]);
    heights.add(rows, fmt::format("using 1:2 with lines title '{}'", name));
    failures += !report(r, "ball_drop: " + name);
    std::vector<Table::Cell> row{name};
    for (auto& c : metric_cells(r)) row.push_back(std::move(c));
    comparison.add_row(std::move(row));
    records.add(r);
  }
  fmt::print(
      "Ball drop: m = {:g} kg, g = {:g} m/s^2, h0 = {:g} m, v0 = {:g} m/s, e = {:g}, law {}, dt = {:g} s, "
      "rtol = {:g}, atol = {:g}, t_end = {:g} s\n\n",
      o.m, o.g, o.h0, o.v0, o.e, describe(law_for(o, o.k)), o.dt, o.rtol, scaled_atol(o), o.t_end);
  fmt::print("{}\n{}", comparison.to_markdown(), ball_references(o));
  if (const SpringContact c = closed_form_contact(o, o.k); !std::isnan(c.max_penetration))
    fmt::print("closed-form first contact at k = {:g}: {}, max penetration {:.6g} m\n", o.k,
               std::isinf(c.duration)   ? "unending (the spring holds the ball)"
               : std::isnan(c.duration) ? "duration unknown (the clamp takes hold again)"
                                        : fmt::format("duration {:.6g} s", c.duration),
               c.max_penetration);
  if (failures > 0)
    throw std::runtime_error(fmt::format("{} of {} methods failed", failures, methods.size()));
  out.add_table("comparison", comparison);
  out.add("contacts.csv", records.contacts.to_csv());
  out.add("apexes.csv", records.apexes.to_csv());
  out.add("samples.csv", records.samples.to_csv());
  out.add("stats.csv", records.stats.to_csv());
  render({"heights", heights.data(),
          "set xlabel 't [s]'\nset ylabel 'height [m]'\nset key outside below\nset grid\nplot " +
              heights.plot()},
         out);
}

}  // namespace contact

using namespace contact;

int program(int argc, char** argv) {
  BallDropOptions o;
  Experiment app("ball_drop",
                 "The ball drop resolved three ways: penalty springs under CVODE, game-style "
                 "fixed-step integration, event-driven impulses.",
                 "results/ball_drop");
  std::vector<std::string> method_names = ball_methods();
  std::string method_help = "methods to run, comma-separated or 'all':";
  for (const auto& m : method_names)
    method_help += fmt::format("\n  {:<28}{}", m, method_info(m).description);
  method_names.insert(method_names.begin(), "all");
  app.add("--method", o.methods, method_help, cli::one_of(method_names, true));
  app.add("--law", o.law, "penalty contact law (damping tuned to --e at the impact speed; Hooke is undamped)",
          cli::one_of(law_names()));
  app.add("--k", o.k, "contact stiffness [N/m]", cli::positive());
  app.add("--e", o.e, "coefficient of restitution", cli::real_in(0, 1, false, false));
  app.add("--m", o.m, "ball mass [kg]", cli::positive());
  app.add("--g", o.g, "gravity [m/s^2]", cli::non_negative());
  app.add("--h0", o.h0, "initial height [m]", cli::positive());
  app.add("--v0", o.v0, "initial vertical velocity [m/s], negative downwards", cli::finite());
  app.add("--dt", o.dt, "fixed step of the game methods and of a fixed-step --integrator [s]",
          cli::positive());
  app.add("--rtol", o.rtol, "relative tolerance of adaptive integrators", cli::real_in(0, 1, true, true));
  app.add("--atol", o.atol,
          "absolute tolerance of adaptive integrators [m, m/s]; 0: 1e-10 per metre of the drop's height "
          "scale h0 + v0^2/(2g)",
          cli::non_negative());
  app.add("--t-end", o.t_end, "final time [s]", cli::positive());
  app.add("--sample-dt", o.sample_dt, "spacing of samples.csv [s]", cli::positive());
  app.add("--integrator", o.integrator, "ODE integrator of the penalty and event-ode methods",
          cli::one_of(integrator_names()));
  app.add("--linear-solver", o.linear_solver,
          "linear solver of implicit SUNDIALS integrators (klu: 'all' leaves out penalty-dq, whose "
          "difference-quotient Jacobian it cannot take)",
          cli::one_of(linear_solver_names()));
  app.add("--jacobian", o.jacobian, "Jacobian of implicit integrators (penalty-dq always uses dq)",
          cli::one_of(jacobian_names()));
  app.add("--max-steps", o.max_steps, "integrator steps allowed between outputs", cli::integer_at_least(1));
  app.add("--max-records", o.max_records,
          "contact records and apexes a run may keep before it fails (a game ball in a bouncing limit "
          "cycle adds two every ~14 ms)",
          cli::integer_in(1, kMaxRecords));
  app.add("--rest-speed", o.rest_speed, "event-driven: outgoing speed below which the ball rests [m/s]",
          cli::positive());
  app.add_flag("--sweep", o.sweep, "run every method for k from --k-min to --k-max and print one table");
  app.add("--k-min", o.k_min, "sweep: smallest k [N/m]", cli::positive());
  app.add("--k-max", o.k_max, "sweep: largest k [N/m]", cli::positive());
  app.add("--per-decade", o.per_decade, "sweep: points per decade of k", cli::integer_in(1, 100));

  return app.run(argc, argv, [&](OutputSet& files) {
    if (o.sweep && !(o.k_max >= o.k_min))
      throw std::invalid_argument(fmt::format(
          "--k-max: value '{}' is below --k-min = {}; accepted range [k-min, inf)", o.k_max, o.k_min));
    check_scales(o);
    const IntegratorOptions integrator = method_for(o, "penalty").integrator;
    validate(integrator);
    note_options_without_effect(o, app, integrator);
    if (o.sweep)
      run_sweep(o, app, files);
    else
      run_single(o, files);
  });
}

int main(int argc, char** argv) { return contact::guarded_main("ball_drop", argc, argv, program); }
