// convergence_k — the penalty solution approaching the rigid (event-driven) one as k -> infinity.
// Ball drop (m = 1 kg, g = 9.81 m/s^2, h0 = 1 m, e = --e): Kelvin–Voigt penalty contacts tuned to
// e, under CVODE BDF (rtol 1e-11, atol 1e-13, switches root-located), against event-driven
// impulses with the exact flight. Errors over the first --bounces bounces: impact times
// max |T_n - T_n^rigid| [s] and apex heights max |h_n - h_n^rigid| / h0. Both close as
// k^(-1/2): a contact lasts ~pi sqrt(m/k), and gravity shifts its restitution by O(g / (w V)).
// The table gives the observed order between consecutive rows (log ratio of errors over log ratio
// of k) and the least-squares exponent (GSL) over all rows. At low k a soft damped spring can hold
// the ball for good (problems.hpp, held_for_good): such a row says so, with no errors.
// Outputs in --out (default results/convergence_k): convergence_k.{csv,md,tex}, rates.{csv,md,tex},
// errors.{png,pdf,gp}, meta.json. Exit codes: 0, 1 solver failure, 2 bad input.
#include "contact_ode/analysis/fit.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/event_driven.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/law_registry.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "output.hpp"
#include "problems.hpp"
#include "process.hpp"
#include "progress.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <iostream>

using namespace contact;

int program(int argc, char** argv) {
  double e = 0.8, k_min = 1e3, k_max = 1e9;
  long bounces = 3, per_decade = 1;
  Experiment app("convergence_k",
                 "Penalty bounce times and apex heights approaching the rigid ones as k grows.",
                 "results/convergence_k");
  app.add("--e", e, "coefficient of restitution", cli::real_in(0, 1, true, false));
  app.add("--k-min", k_min, "smallest k [N/m]", cli::positive());
  app.add("--k-max", k_max, "largest k [N/m]", cli::positive());
  app.add("--per-decade", per_decade, "points per decade of k", cli::integer_in(1, 100));
  app.add("--bounces", bounces, "bounces compared", cli::integer_at_least(1));
  return app.run(argc, argv, [&](OutputSet& files) {
    if (!(k_max > k_min)) {
      throw std::invalid_argument(fmt::format(
          "--k-max: value '{}' is not above --k-min = {}; accepted range (k-min, inf)", k_max, k_min));
    }
    const double m = 1.0, g = 9.81, h0 = 1.0;
    // Long enough for `bounces` impacts and apexes: T_{n+1} = T_n + 2 e^n t0.
    const double t0 = std::sqrt(2 * h0 / g);
    // Summed in closed form (a loop over --bounces 2147483647 terms took 20 s before the refusal).
    const auto b1 = static_cast<double>(bounces) + 1;
    const double t_end = t0 + 2 * t0 * (e < 1 ? -std::expm1(b1 * std::log(e)) / (1 - e) : b1) + 0.1;

    const BallDrop rigid_model({m, g, h0, 0.0, e, Hooke{1.0}});
    const RunResult rigid = solve(rigid_model, {.name = "event-exact"}, {.t_end = t_end, .sample_dt = t_end});
    const auto nb = static_cast<std::size_t>(bounces);
    if (!rigid.ok()) throw std::runtime_error("the rigid reference failed: " + rigid.message);
    const double rest = EventOptions{}.rest_speed, V = std::sqrt(2 * g * h0);
    if (rigid.apexes.empty()) {  // not one apex: --e is what is wrong, whatever --bounces
      throw std::invalid_argument(fmt::format(
          "--e: value '{:g}' leaves the rigid ball no apex: its rebound speed e V = {:.3g} m/s "
          "is below the rest speed ({:g} m/s); accepted --e >= {:g} (V = {:.3g} m/s from h0 = {:g} m)",
          e, e * V, rest, cli::rounded_up(rest / V), V, h0));
    }
    if (rigid.contacts.size() < nb || rigid.apexes.size() < nb)  // it rested first (a small e)
      throw std::invalid_argument(fmt::format(
          "--bounces: value '{}' is more than the rigid ball makes at --e {:g}: {} apexes, then its "
          "rebound speed e^n V falls below the rest speed ({:g} m/s); accepted range [1, {}]",
          bounces, e, rigid.apexes.size(), rest, rigid.apexes.size()));
    Table table({"k_N_per_m", "impact_time_error_s", "order_time", "apex_height_error_rel", "order_apex",
                 "rhs_evals", "status"});
    table.set_latex_header({"$k$ [N/m]", "$\\max|T_n - T_n^{\\mathrm{rigid}}|$ [s]", "order",
                            "$\\max|h_n - h_n^{\\mathrm{rigid}}|/h_0$", "order", "evaluations", "status"});
    std::vector<double> ks, time_err, apex_err;
    const std::vector<double> grid = log_grid(k_min, k_max, per_decade);
    Progress progress("convergence_k", grid.size());
    std::string data;
    for (const double k : grid) {
      progress.step(fmt::format("k = {:.3g}", k));
      Method penalty{.name = "penalty"};
      penalty.integrator.rtol = 1e-11;
      penalty.integrator.atol = 1e-13;
      penalty.integrator.max_steps = 1000000;
      const BallDropParams p{m, g, h0, 0.0, e, make_law("kelvin-voigt", {.k = k, .m = m, .e = e})};
      const auto run = [&](double t) {
        return require(solve(BallDrop(p), penalty, {.t_end = t, .sample_dt = t}), fmt::format("k = {:g}", k));
      };
      // The rigid span first; the penalty ball's contacts take time (each less than a damped
      // period): where its bounces need it, nb + 1 periods more.
      RunResult r = run(t_end);
      if (r.apexes.size() < nb && !held_for_good(r, p))
        r = run(t_end + static_cast<double>(nb + 1) * damped_period(p));
      if (r.apexes.size() < nb && held_for_good(r, p)) {  // a soft spring holds the ball: no errors
        table.add_row(
            {k, NAN, NAN, NAN, NAN, r.stats.rhs_evals, fmt::format("held in contact {}", r.contacts.size())});
        continue;
      }
      if (r.contacts.size() < nb || r.apexes.size() < nb) {
        throw std::runtime_error(
            fmt::format("k = {:g}: the penalty run made {} contacts and {} apexes by t = {:.6g} s, "
                        "fewer than the {} bounces compared; lower --bounces or raise --k-min",
                        k, r.contacts.size(), r.apexes.size(), r.samples.back().t, nb));
      }
      double te = 0, ae = 0;
      for (std::size_t b = 0; b < nb; ++b) {
        te = std::max(te, std::abs(r.contacts[b].t_begin - rigid.contacts[b].t_begin));
        ae = std::max(ae, std::abs(r.apexes[b].gap - rigid.apexes[b].gap) / h0);
      }
      const double order_t = ks.empty() ? std::nan("") : observed_order(ks.back(), time_err.back(), k, te);
      const double order_a = ks.empty() ? std::nan("") : observed_order(ks.back(), apex_err.back(), k, ae);
      ks.push_back(k);
      time_err.push_back(te);
      apex_err.push_back(ae);
      table.add_row({k, te, order_t, ae, order_a, r.stats.rhs_evals, std::string("ok")});
      data += fmt::format("{},{},{}\n", k, te, ae);
    }
    Table rates({"quantity", "fitted_exponent", "exponent_sd", "expected"});
    Series lines;  // none when a soft spring held the ball at every k
    if (ks.size() >= 2) {
      const PowerFit ft = fit_power_law(ks, time_err), fa = fit_power_law(ks, apex_err);
      rates.add_row({std::string("impact_time_error"), ft.exponent, ft.exponent_sd, -0.5});
      rates.add_row({std::string("apex_height_error"), fa.exponent, fa.exponent_sd, -0.5});
    }
    if (!ks.empty()) {
      lines.add(data, "using 1:2 with linespoints title 'impact time [s]'");
      lines.add(data, "using 1:3 with linespoints title 'apex height / h0'");
    }
    files.add_table("convergence_k", table);
    files.add_table("rates", rates);
    render({"errors", lines.data(), loglog("k [N/m]", "error") + "set key bottom left\nplot " + lines.plot()},
           files);
    fmt::print("Penalty -> rigid as k grows (e = {:g}, first {} bounces)\n\n{}\nFitted rates:\n\n{}", e,
               bounces, table.to_markdown(), rates.to_markdown());
  });
}

int main(int argc, char** argv) { return contact::guarded_main("convergence_k", argc, argv, program); }
