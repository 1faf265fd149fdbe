// k_sweep — what the spring constant k does to a penalty contact, and what it costs.
// The ball drop (m = 1 kg, g = 9.81 m/s^2, h0 = 1 m) under CVODE BDF (rtol 1e-10, atol 1e-12,
// contact switches root-located) for k = 1e2 ... 1e10 N/m, --per-decade points per decade, with
// three laws: Hooke (undamped), Kelvin–Voigt tuned to e = --e (unclamped and clamped). For the
// first contact: maximum penetration, duration, restitution, the energy left at the first apex,
// and CVODE's cost per contact (steps, right-hand sides, Jacobians, Newton iterations, failed
// steps); the largest stable explicit and semi-implicit Euler steps for that contact (linearised:
// 2 zeta / w and 2 (sqrt(zeta^2 + 1) - zeta) / w, analysis/contact_advisor.hpp); beside them the
// closed forms (exact, gravity included: references.hpp) and the exponents of
// penetration and duration against k fitted by least squares in log-log (GSL) over k >= 1e4,
// where gravity's share g / (w V) is below 2 %. A row where a soft damped spring holds the ball for
// good is "held", NaN for the bounce, out of figures and fits. Under mpirun cases go over ranks.
// Outputs in --out (default results/k_sweep): k_sweep and exponents (.csv/.md/.tex), figures
// penetration, duration, cost, stable_dt (.png/.pdf/.gp), meta.json. Exit: 0, 1 solver failure, 2 bad input.
#include "contact_ode/analysis/fit.hpp"
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/law_registry.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "problems.hpp"
#include "process.hpp"
#include "progress.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

using namespace contact;

namespace {

// The linear laws, whose penetration and duration have closed forms against k.
const std::vector<std::string> kLaws = {"hooke", "kelvin-voigt", "kelvin-voigt-clamped"};

// A log-log figure of data column `ycol` (and its closed form `ref_col`, if > 0) against k, per law.
Figure k_figure(const std::string& name, const std::string& ylabel, int ycol, int ref_col) {
  std::string plot = loglog("k [N/m]", ylabel) + "set key bottom left\nplot ";
  for (std::size_t i = 0; i < kLaws.size(); ++i) {
    if (i) plot += ", ";
    plot += fmt::format("'data.csv' using ($2 == {} ? $1 : 1/0):{} with points pt {} title '{}'", i, ycol,
                        5 + 2 * static_cast<int>(i), kLaws[i]);
    if (ref_col > 0)
      plot += fmt::format(", '' using ($2 == {} ? $1 : 1/0):{} with lines dt 2 title '{} closed form'", i,
                          ref_col, kLaws[i]);
  }
  return {name, "", plot};
}

}  // namespace

int program(int argc, char** argv) {
  double e = 0.8, k_min = 1e2, k_max = 1e10;
  long per_decade = 3;
  Experiment app("k_sweep",
                 "What k does to a penalty contact: penetration, duration, restitution, cost, stable steps.",
                 "results/k_sweep");
  app.add("--e", e, "target restitution of the Kelvin-Voigt laws", cli::real_in(0, 1, true, false));
  app.add("--k-min", k_min, "smallest k [N/m]", cli::positive());
  app.add("--k-max", k_max, "largest k [N/m]", cli::positive());
  app.add("--per-decade", per_decade, "points per decade of k", cli::integer_in(1, 100));
  return app.run(argc, argv, [&](OutputSet& files) {
    if (!(k_max >= k_min))
      throw std::invalid_argument(fmt::format(
          "--k-max: value '{}' is below --k-min = {}; accepted range [k-min, inf)", k_max, k_min));
    const double m = 1.0, g = 9.81, h0 = 1.0, V = std::sqrt(2 * g * h0);
    const std::vector<double> grid = log_grid(k_min, k_max, per_decade);
    Table table({"k_N_per_m", "law", "penetration_m", "closed_form_penetration_m", "duration_s",
                 "closed_form_duration_s", "restitution", "energy_after_first_bounce_rel",
                 "steps_per_contact", "rhs_per_contact", "jac_per_contact", "newton_per_contact",
                 "failed_steps", "euler_max_dt_s", "symplectic_max_dt_s", "first_bounce"});
    std::string data;  // for the figures: k, law index, the numeric columns in table order
    Progress progress("k_sweep", kLaws.size() * grid.size());
    const auto cases = app.share(kLaws.size() * grid.size(), [&](std::size_t i) -> nlohmann::json {
      const std::string& law = kLaws[i / grid.size()];
      const double k = grid[i % grid.size()];
      progress.step(fmt::format("{} k = {:.3g}", law, k));
      Method penalty{.name = "penalty"};
      penalty.integrator.rtol = 1e-10;
      penalty.integrator.atol = 1e-12;
      penalty.integrator.max_steps = 1000000;
      const BallDropParams p{m, g, h0, 0.0, e, make_law(law, {.k = k, .m = m, .e = e})};
      const double t_end = first_bounce_window(p, 1.6);
      const std::string what = fmt::format("{} at k = {:g}", law, k);
      const RunResult r = require(solve(BallDrop(p), penalty, {.t_end = t_end, .sample_dt = t_end}), what);
      const std::string status = first_bounce(r, p, what);  // or the spring holds it (NaN below)
      const auto& c = r.contacts[0];
      const double n = static_cast<double>(r.contacts.size());
      const auto per = [n](long count) { return static_cast<double>(count) / n; };
      const double left = r.apexes.empty() ? NAN : r.apexes[0].energy / r.energy0;
      return {{"penetration", c.max_penetration}, {"duration", c.duration()},
              {"restitution", c.restitution()},   {"energy_left", left},
              {"steps", per(r.stats.steps)},      {"rhs", per(r.stats.rhs_evals)},
              {"jac", per(r.stats.jac_evals)},    {"newton", per(r.stats.newton_iters)},
              {"failed", r.stats.failed_steps},   {"status", status}};
    });
    if (!cases) return;  // another MPI rank: its share is done
    std::map<std::string, std::vector<double>> fit_k, fit_pen, fit_dur;  // k >= 1e4, per law
    for (std::size_t i = 0; i < cases->size(); ++i) {
      const std::size_t li = i / grid.size();
      const std::string& law = kLaws[li];
      const double k = grid[i % grid.size()];
      const auto get = [&c = (*cases)[i]](const char* key) { return c[key].get<double>(); };
      const SpringContact ref = linear_law_first_contact(law, m, k, e, V, g);
      const double zeta = law_info(law).damped ? damping_ratio_for_restitution(e) : 0.0, w = std::sqrt(k / m);
      const double euler_dt = 2 * zeta / w, symplectic_dt = 2 * (std::sqrt(zeta * zeta + 1) - zeta) / w;
      const std::string status = (*cases)[i]["status"];
      table.add_row({k, law, get("penetration"), ref.max_penetration, get("duration"), ref.duration,
                     get("restitution"), get("energy_left"), get("steps"), get("rhs"), get("jac"),
                     get("newton"), static_cast<long>(get("failed")), euler_dt, symplectic_dt, status});
      if (status == "held") continue;  // no bounce: out of the figures and fits
      data += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", k, li, get("penetration"),
                          ref.max_penetration, get("duration"), ref.duration, get("steps"), get("rhs"),
                          euler_dt > 0 ? euler_dt : NAN, symplectic_dt, get("restitution"));
      if (k < 1e4) continue;
      fit_k[law].push_back(k);
      fit_pen[law].push_back(get("penetration"));
      fit_dur[law].push_back(get("duration"));
    }
    Table exponents({"law", "penetration_exponent", "penetration_exponent_sd", "duration_exponent",
                     "duration_exponent_sd", "expected"});
    exponents.set_latex_header({"law", "penetration", "sd", "duration", "sd", "expected"});
    for (const auto& law : kLaws) {
      if (fit_k[law].size() < 2) continue;
      const PowerFit p = fit_power_law(fit_k[law], fit_pen[law]), d = fit_power_law(fit_k[law], fit_dur[law]);
      exponents.add_row({law, p.exponent, p.exponent_sd, d.exponent, d.exponent_sd, std::string("-1/2")});
    }
    files.add_table("k_sweep", table);
    files.add_table("exponents", exponents);
    // data columns: 1 k, 2 law, 3 pen, 4 ref, 5 dur, 6 ref, 7 steps, 8 rhs, 9 euler dt, 10 sympl. dt, 11 e
    for (Figure f : {k_figure("penetration", "maximum penetration [m]", 3, 4),
                     k_figure("duration", "contact duration [s]", 5, 6),
                     k_figure("cost", "CVODE right-hand sides per contact", 8, 0),
                     k_figure("stable_dt", "largest stable semi-implicit Euler step [s]", 10, 0)}) {
      f.data = data;
      render(f, files);
    }
    fmt::print(
        "k sweep: ball drop, m = {:g} kg, h0 = {:g} m, e = {:g}, CVODE BDF rtol 1e-10\n\n{}\nFitted "
        "exponents (k >= 1e4):\n\n{}",
        m, h0, e, table.to_markdown(), exponents.to_markdown());
  });
}

int main(int argc, char** argv) { return contact::guarded_main("k_sweep", argc, argv, program); }
