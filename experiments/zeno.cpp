// zeno — the ball drop near the accumulation of bounces, t_inf = t0 (1+e)/(1-e) (4.06 s for the
// defaults), by every method run past it (t_end = --t-end).
// For each: how many contacts, how long before t_inf the last one began (for the event-driven
// runs, where their rest guard ended the cascade: 2 t0 e^n / (1 - e) after n impacts), when the
// motion stops (the first sample after which the speed stays below --rest-speed), where the ball
// ends up, and the lowest height it reached: a ball falling through the floor shows as a minimum
// far below the contact's penetration. The penalty ball settles onto its spring at the static
// deflection m g / k; the game loop's contact flickers every step at rest.
// Outputs in --out (default results/zeno): zeno.{csv,md,tex}, heights.{png,pdf,gp}, meta.json.
// Exit codes: 0, 1 solver failure, 2 bad input.
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/law_registry.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "output.hpp"
#include "process.hpp"
#include "progress.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <iostream>

using namespace contact;

namespace {
constexpr double kSampleDt = 1e-3;  // the samples' spacing [s]
}  // namespace

int program(int argc, char** argv) {
  double e = 0.8, k = 1e5, t_end = 6.0, dt = 1e-3, rest_speed = 1e-3;
  Experiment app("zeno", "The ball drop near the accumulation of bounces, by every method.", "results/zeno");
  app.add("--e", e, "coefficient of restitution", cli::real_in(0, 1, true, true));
  app.add("--k", k, "penalty stiffness [N/m]", cli::positive());
  // A run keeps at most RunLimits::max_samples samples: past that many of its sample_dt every run
  // failed at t = 0.
  const double longest = kSampleDt * static_cast<double>(RunLimits{}.max_samples);
  app.add("--t-end", t_end,
          fmt::format("final time [s] (its {:g} s samples: below {:g} s)", kSampleDt, longest),
          cli::real_in(0, longest, true, true));
  app.add("--dt", dt, "game step [s]", cli::positive());
  app.add("--rest-speed", rest_speed, "speed below which the motion counts as stopped [m/s]",
          cli::positive());
  return app.run(argc, argv, [&](OutputSet& files) {
    const double m = 1.0, g = 9.81, h0 = 1.0;
    const RigidBounces ref(h0, 0.0, g, e);
    const BallDrop model({m, g, h0, 0.0, e, make_law("kelvin-voigt", {.k = k, .m = m, .e = e})});
    Method method{.dt = dt};
    method.integrator.max_steps = 1000000;

    Table table({"method", "status", "contacts", "last_contact_before_zeno_s", "rest_time_s", "zeno_time_s",
                 "final_height_m", "static_deflection_m", "min_height_m", "rhs_evals"});
    table.set_latex_header({"method", "status", "contacts", "$t_\\infty -$ last [s]", "rest at [s]",
                            "$t_\\infty$ [s]", "final height [m]", "$mg/k$ [m]", "lowest [m]",
                            "evaluations"});
    Series heights;
    const std::vector<std::string> methods = {"event-exact", "event-ode", "penalty", "game-symplectic",
                                              "game-symplectic-spring"};
    std::vector<PlannedRun> planned;
    for (const std::string& name : methods) planned.push_back({name, {.name = name, .dt = dt}, t_end});
    refuse_dt_beyond_work_limit(planned);
    Progress progress("zeno", methods.size());
    for (std::size_t mi = 0; mi < methods.size(); ++mi) {
      progress.step(methods[mi]);
      method.name = methods[mi];
      const RunResult r = require(
          solve(model, method, {.t_end = t_end, .sample_dt = kSampleDt, .progress = progress.follow(t_end)}),
          methods[mi]);
      double rest = std::nan(""), lowest = INFINITY;
      for (std::size_t i = r.samples.size(); i-- > 0;) {
        if (std::abs(r.samples[i].y[1]) >= rest_speed) break;
        rest = r.samples[i].t;
      }
      std::string rows;
      for (const auto& smp : r.samples) {
        lowest = std::min(lowest, smp.y[0]);
        rows += fmt::format("{},{}\n", smp.t, smp.y[0]);
      }
      heights.add(rows, fmt::format("using 1:2 with lines title '{}'", methods[mi]));
      const double last = r.contacts.empty() ? std::nan("") : r.contacts.back().t_begin;
      table.add_row({methods[mi], std::string(to_string(r.status)), static_cast<long>(r.contacts.size()),
                     ref.zeno_time() - last, rest, ref.zeno_time(), r.samples.back().y[0], m * g / k, lowest,
                     r.stats.rhs_evals});
    }
    std::string plot = fmt::format(
        "set xlabel 't [s]'\nset ylabel 'height [m]'\nset key top right\nset grid\n"
        "set arrow from {0}, graph 0 to {0}, graph 1 nohead dt 2\nset label 'Zeno time' at {0}, graph "
        "0.9\nplot {1}",
        ref.zeno_time(), heights.plot());
    files.add_table("zeno", table);
    render({"heights", heights.data(), plot}, files);
    fmt::print("Zeno: ball drop with e = {:g}, accumulation at t_inf = {:.6g} s\n\n{}", e, ref.zeno_time(),
               table.to_markdown());
  });
}

int main(int argc, char** argv) { return contact::guarded_main("zeno", argc, argv, program); }
