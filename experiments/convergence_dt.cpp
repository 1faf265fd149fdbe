// convergence_dt — observed orders of every integrator on the penalty ball drop, switches located or not.
// Problem: 1 kg dropped on a Hooke spring (--k) to t = --t-final (1.5 s: two contacts, four kinks) from
// --heights heights in [1, 1.25) m, so that the kinks fall at every phase of a fixed step. Error of a
// drop: max(|x - x*| / h0, |v - v*| / V) at t-final against the closed form; a row reports its maximum
// and RMS over the heights and the CPU time per solve. Fixed steps dt = --dt-max / 2^j, j = 0..--halvings
// (stopping at the first error below 1e-9: errors_down_to); rtol = 10^-3 .. --tol-min, atol = rtol / 100.
// "unlocated": steps straddle the kink of F = k max(-x, 0), so an order p > 2 drops to 2. Fitted order:
// the least-squares log-log slope (GSL) of the maximum error over the five finest rows with 1e-9 < error
// < 1e-2. Under mpirun the ladders (integrator, location, fixed or adaptive) go over the ranks. A failed
// run (say a stage's Newton iteration across an unlocated kink) is a row with its status, no error.
// Outputs: fixed_step, adaptive, orders (.csv/.md/.tex), figures, meta.json. Exit 0, 1, 2 bad input.
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "problems.hpp"
#include "process.hpp"
#include "progress.hpp"
#include "sweep_setting.hpp"

#include <fmt/format.h>

#include <cmath>

using namespace contact;

namespace {

// The fit's range: errors below 1e-2 (the leading term dominates) and above the floor of root location
constexpr double kRoundOff = 1e-9, kAsymptotic = 1e-2;  // and dense output (RK4's located rows flatten)
constexpr std::size_t kFitRows = 5;

struct Ladder {
  std::string integrator;
  bool located, fixed;        // switches located; fixed steps (else tolerances)
  std::vector<double> steps;  // dt or rtol, coarsest first
};
using Points = std::map<bool, std::map<std::string, std::vector<ConvergencePoint>>>;  // [located][integrator]

}  // namespace

int program(int argc, char** argv) {
  double k = 1e4, t_final = 1.5, dt_max = 2e-3, tol_min = 1e-10;
  long halvings = 6, heights = 3;
  std::string integrators = "all";
  Experiment app("convergence_dt",
                 "Observed orders of every integrator on the penalty ball drop, kinks located or not.",
                 "results/convergence_dt");
  app.add("--k", k, "spring stiffness [N/m]", cli::positive());
  app.add("--t-final", t_final, "time at which the error is measured [s]", cli::positive());
  app.add("--dt-max", dt_max, "largest fixed step [s]", cli::positive());
  app.add("--halvings", halvings, "fixed steps: dt-max halved this many times", cli::integer_at_least(1));
  app.add("--tol-min", tol_min, "tightest tolerance (decades from 1e-3 down: 7e-6 stops at 1e-5)",
          cli::real_in(1e-14, 1e-4, false, false));
  app.add("--heights", heights, "drop heights per row (the kinks' phases in the step)",
          cli::integer_in(1, 100));
  app.add("--integrators", integrators, "integrators, comma-separated or 'all'",
          cli::some_of(integrator_names()));
  return app.run(argc, argv, [&](OutputSet& files) {
    const auto dts = halved_dt_max(dt_max, halvings, t_final);
    const auto drops = ball_problems_over_heights(k, t_final, static_cast<std::size_t>(heights));
    const auto chosen = converging_integrators(cli::chosen(integrators, integrator_names()), integrators);
    std::vector<Ladder> ladders;
    for (const auto& name : chosen)
      for (const bool located : {false, true}) {
        if (integrator_info(name).fixed_step_capable) ladders.push_back({name, located, true, dts});
        if (integrator_info(name).adaptive) ladders.push_back({name, located, false, decades(1e-3, tol_min)});
      }
    Progress progress("convergence_dt", ladders.size());
    const auto results = app.share(ladders.size(), [&](std::size_t i) -> nlohmann::json {
      const Ladder& l = ladders[i];
      progress.step(l.integrator + (l.located ? " located" : " unlocated") + (l.fixed ? " dt" : " rtol"));
      return nlohmann::json(errors_down_to(l.steps, l.fixed ? kRoundOff : 0.0, [&](double step) {
        PenaltyOptions o{.integrator = {.method = l.integrator, .max_steps = kSweepMaxSteps},
                         .locate_switches = l.located};
        o.integrator = with_setting(o.integrator, l.fixed, step);
        return error_over(drops, [&](const Problem& drop) {
          return run_penalty(*drop.model, o, {.t_end = t_final, .sample_dt = t_final});
        });
      }));
    });
    if (!results) return;  // another MPI rank: its share is done
    const auto columns = [](const char* step) {
      return std::vector<std::string>{"integrator",     "events",    step,    "error_max", "error_rms",
                                      "observed_order", "rhs_evals", "cpu_s", "status"};
    };
    Table fixed(columns("dt_s")), adaptive(columns("rtol"));
    Points fixed_points, adaptive_points;
    std::map<bool, std::map<std::string, double>> tightest_rhs;  // [located][integrator], NaN: it failed
    for (std::size_t i = 0; i < ladders.size(); ++i)
      for (std::size_t j = 0; j < (*results)[i].size(); ++j) {
        const Ladder& c = ladders[i];
        const double step = c.steps[j];
        const auto r = (*results)[i][j].get<ErrorSpread>();
        const std::string events = c.located ? "located" : "unlocated";
        auto& points = (c.fixed ? fixed_points : adaptive_points)[c.located][c.integrator];
        report(r, fmt::format("convergence_dt: {} {} ({} {:g})", c.integrator, events,
                              c.fixed ? "dt" : "rtol", step));
        const double order = points.empty() || !r.ok()
                                 ? std::nan("")
                                 : observed_order(points.back().step, points.back().error, step, r.max);
        if (r.ok()) points.push_back({step, r.max, std::lround(r.rhs)});
        if (!c.fixed) tightest_rhs[c.located][c.integrator] = r.ok() ? std::round(r.rhs) : std::nan("");
        Table& table = c.fixed ? fixed : adaptive;
        table.add_row(
            {c.integrator, events, step, r.max, r.rms, order, std::lround(r.rhs), r.cpu_s, r.status});
      }
    Table orders({"integrator", "order", "expected_unlocated", "fixed_order_unlocated", "fixed_order_located",
                  "tol_exponent_unlocated", "tol_exponent_located", "rhs_evals_tightest_unlocated",
                  "rhs_evals_tightest_located"});
    orders.set_latex_header({"integrator", "$p$", "expected\nunlocated", "fixed $\\Delta t$\nunlocated",
                             "fixed $\\Delta t$\nlocated", "rtol exponent\nunlocated",
                             "rtol exponent\nlocated", "evaluations\nunlocated", "evaluations\nlocated"});
    const auto fit = [](Points& sweep, bool located, const std::string& name) {
      const auto it = sweep[located].find(name);  // (find: no empty series for the figures)
      return it == sweep[located].end() ? std::nan("")
                                        : fitted_order(it->second, kRoundOff, kFitRows, kAsymptotic);
    };
    const auto cost = [&](bool located, const std::string& name) {
      return tightest_rhs[located].contains(name) ? tightest_rhs[located][name] : std::nan("");
    };
    for (const auto& name : chosen) {
      // The formula's order where a fixed step runs it (the adaptive codes vary theirs).
      const double p = integrator_info(name).fixed_step_capable ? integrator_info(name).order : std::nan("");
      orders.add_row({name, p, std::min(p, 2.0), fit(fixed_points, false, name),
                      fit(fixed_points, true, name), fit(adaptive_points, false, name),
                      fit(adaptive_points, true, name), cost(false, name), cost(true, name)});
    }
    files.add_table("fixed_step", fixed);
    files.add_table("adaptive", adaptive);
    files.add_table("orders", orders);
    const std::string ylabel = "max error at t_{final} over the heights";
    for (const bool located : {false, true}) {
      const std::string events = located ? "located" : "unlocated";
      if (const auto& f = fixed_points[located]; !f.empty())
        render(convergence_figure("fixed_" + events, "dt [s]", ylabel, {f.begin(), f.end()}, {1, 2, 4}),
               files);
      if (const auto& a = adaptive_points[located]; !a.empty())
        render(convergence_figure("adaptive_" + events, "rtol", ylabel, {a.begin(), a.end()}, {1}), files);
    }
    fmt::print(
        "Observed orders on the penalty ball drop (k = {:g} N/m, error at t = {:g} s, {} heights)\n\n{}", k,
        t_final, heights, orders.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("convergence_dt", argc, argv, program); }
