// stability_map — game integration of a spring contact over the (k, dt) plane, on the w dt axis.
// One isolated contact (no gravity, m = 1 kg, entering at 1 m/s) with the penalty spring
// (Hooke: undamped, so any gain or loss is the scheme's) advanced by explicit and semi-implicit
// Euler at fixed dt, for k = 1e2, 1e4, 1e6 N/m and w dt = sqrt(k/m) dt from 0.01 to 4. The ball
// starts half a step's travel above the floor, so every (k, dt) with the same w dt sees the same
// scaled motion: the curves for different k must coincide. Reported: the effective restitution
// (exit / entry speed) and the energy ratio, against the analytic references: explicit Euler
// multiplies the oscillator's energy by (1 + (w dt)^2) every step in contact; semi-implicit Euler
// keeps it within (1 + w dt/2)/(1 - w dt/2) of the entry value below w dt = 2 and is unstable above.
// Outputs in --out (default results/stability_map): stability.{csv,md,tex},
// restitution.{png,pdf,gp}, meta.json; under mpirun the (k, scheme, w dt) runs are dealt over the
// ranks. Exit codes: 0, 1 failure, 2 bad input.
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/game_step.hpp"
#include "contact_ode/models/ball_drop.hpp"
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

int program(int argc, char** argv) {
  long points = 40;
  double wdt_max = 4.0;
  Experiment app(
      "stability_map",
      "Game integration of a spring contact over the (k, dt) plane: restitution and energy against w dt.",
      "results/stability_map");
  app.add("--points", points, "w dt values, log-spaced from 0.01", cli::integer_in(2, 10000));
  app.add("--wdt-max", wdt_max, "largest w dt", cli::real_in(0.01, 100, true, false));
  return app.run(argc, argv, [&](OutputSet& files) {
    const double m = 1.0, V = 1.0;
    Table table(
        {"k_N_per_m", "scheme", "omega_dt", "dt_s", "restitution", "energy_ratio", "reference_bound"});
    const std::vector<double> ks = {1e2, 1e4, 1e6};
    const FixedStepScheme schemes[] = {FixedStepScheme::ExplicitEuler, FixedStepScheme::SemiImplicitEuler};
    const auto per_k = 2 * static_cast<std::size_t>(points);  // case i: k i / per_k, scheme_of(i)
    const auto scheme_of = [&](std::size_t i) { return i % per_k / static_cast<std::size_t>(points); };
    Progress progress("stability_map", ks.size() * per_k);
    const auto results = app.share(ks.size() * per_k, [&](std::size_t i) -> nlohmann::json {
      const std::size_t ki = i / per_k;
      const auto scheme = schemes[scheme_of(i)];
      const auto j = static_cast<double>(i % static_cast<std::size_t>(points));
      const double k = ks[ki], w = std::sqrt(k / m);
      const double wdt = 0.01 * std::pow(wdt_max / 0.01, j / static_cast<double>(points - 1));
      const double dt = wdt / w;
      progress.step(fmt::format("k = {:g} {} w dt = {:.3g}", k, to_string(scheme), wdt));
      const double h0 = 0.5 * V * dt;
      const BallDrop model({m, 0.0, h0, -V, 1.0, Hooke{k}});
      // Long enough for the slowest contact (about pi/w plus the steps it takes) to end.
      const double t_end = h0 / V + 20 * M_PI / w + 10 * dt;
      const RunResult r = run_game(model, {.dt = dt, .scheme = scheme, .resolution = GameResolution::Spring},
                                   {.t_end = t_end, .sample_dt = t_end});
      double e = std::nan(""), ratio = std::nan("");
      if (r.ok() && !r.contacts.empty() && r.contacts.front().closed()) {
        e = r.contacts.front().restitution();
        ratio = e * e;  // kinetic energy out over in: the spring holds none once the ball has left
      } else if (!r.ok() || (!r.contacts.empty() && !r.contacts.front().closed())) {
        e = ratio = std::numeric_limits<double>::infinity();  // unstable: never let go, or blew up
      }
      const double bound =
          scheme == FixedStepScheme::SemiImplicitEuler
              ? (wdt < 2 ? (1 + wdt / 2) / (1 - wdt / 2) : std::numeric_limits<double>::infinity())
              : std::nan("");
      return row_to_json({k, std::string(to_string(scheme)), wdt, dt, e, ratio, bound});
    });
    if (!results) return;  // another MPI rank: its share is done
    std::string data;
    for (std::size_t i = 0; i < results->size(); ++i) {
      const auto row = row_from_json((*results)[i]);
      const double wdt = std::get<double>(row[2]), e = std::get<double>(row[4]);
      if (std::isfinite(e)) data += fmt::format("{},{},{},{}\n", i / per_k, scheme_of(i), wdt, e);
      table.add_row(row);
    }
    std::string plot =
        "set logscale xy\nset xlabel 'omega dt'\nset ylabel 'effective restitution (exit / entry speed)'\n"
        "set key top left\nset grid\nset arrow from 2, graph 0 to 2, graph 1 nohead dt 2\n"
        "set label 'omega dt = 2' at 2.05, graph 0.1\nplot ";
    for (std::size_t ki = 0; ki < ks.size(); ++ki)
      for (int s = 0; s < 2; ++s)
        plot += fmt::format(
            "{}'data.csv' using ($1 == {} && $2 == {} ? $3 : 1/0):4 with linespoints pt {} title '{} k = "
            "{:g}'",
            ki || s ? ", " : "", ki, s, 4 + 2 * static_cast<int>(ki) + s, s ? "semi-implicit" : "explicit",
            ks[ki]);
    plot += ", sqrt((1 + x/2)/(1 - x/2)) title 'semi-implicit bound' dt 3 lc rgb 'black'";
    files.add_table("stability", table);
    render({"restitution", data, plot}, files);
    fmt::print("Stability map: spring contact under game integration (Hooke, m = 1 kg, 1 m/s)\n\n{}",
               table.to_markdown());
  });
}

int main(int argc, char** argv) { return contact::guarded_main("stability_map", argc, argv, program); }
