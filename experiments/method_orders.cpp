// method_orders — the order in dt of every fixed-step method, impacts included.
// Problem (problems.hpp): 1 kg dropped from 1 m, e = 1, Hooke spring k = --k; error at
// t = --t-final (1.5 s: two impacts) in max(|x - x*| / h0, |v - v*| / V). Each method is measured
// against the exact solution of its own model: the spring methods (the contact law matters:
// game-*-spring, game-implicit-spring, xpbd) against the Hooke spring's closed form, the impulse
// methods (game projection + impulse, sequential impulses, soft step, Moreau–Jean) against the
// rigid bounce. dt = --dt-max / 2^j, j = 0 .. --halvings; the fitted order is the least-squares
// log-log slope (GSL) over the four finest rows with error > 1e-12. A time-stepping scheme that
// resolves an impact inside a step commits an O(dt) error in the impact's timing, so every
// impulse method is expected at order <= 1 whatever its smooth order; the spring methods resolve
// the contact and keep their own order (1 for the Euler family) while dt is well below the
// contact time pi sqrt(m/k) (31 ms at the default k).
// Outputs in --out (default results/method_orders): errors.{csv,md,tex}, orders.{csv,md,tex},
// errors.{png,pdf,gp}, meta.json; under mpirun the (method, dt) runs are dealt over the ranks.
// Exit codes: 0, 1 solver failure, 2 bad input.
#include "contact_ode/analysis/fit.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/method_registry.hpp"
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

constexpr double kFloor = 1e-12;  // below: round-off of the closed forms' impact times
constexpr std::size_t kFitRows = 4;

// Every fixed-step method that can run the ball drop.
std::vector<std::string> fixed_step_methods() {
  std::vector<std::string> names;
  for (const auto& name : methods_for(*ball_problem(1e4, 1.0).model))
    if (method_info(name).fixed_step) names.push_back(name);
  return names;
}

}  // namespace

int program(int argc, char** argv) {
  double k = 1e4, t_final = 1.5, dt_max = 2e-3;
  long halvings = 6;
  std::string methods = "all";
  Experiment app("method_orders",
                 "The order in dt of every fixed-step method on a bouncing ball, impacts included.",
                 "results/method_orders");
  app.add("--k", k, "spring stiffness of the spring methods [N/m]", cli::positive());
  app.add("--t-final", t_final, "time at which the error is measured [s]", cli::positive());
  app.add("--dt-max", dt_max, "largest step [s]", cli::positive());
  app.add("--halvings", halvings, "dt-max halved this many times", cli::integer_in(1, 20));
  app.add("--methods", methods, "fixed-step methods, comma-separated or 'all'",
          cli::some_of(fixed_step_methods()));
  return app.run(argc, argv, [&](OutputSet& files) {
    const auto dts = halved_dt_max(dt_max, halvings, t_final);  // at most 1e7 steps a run
    const Problem ball = ball_problem(k, t_final);
    const auto chosen = cli::chosen(methods, fixed_step_methods());
    Table errors({"method", "reference", "dt_s", "error", "observed_order", "rhs_evals"});
    Table orders({"method", "reference", "fitted_order", "finest_error"});
    Series figure;
    const std::size_t per_method = dts.size();
    const auto step = [&](std::size_t i) { return dts[i % per_method]; };
    Progress progress("method_orders", chosen.size() * per_method);
    const auto results = app.share(chosen.size() * per_method, [&](std::size_t i) -> nlohmann::json {
      const std::string& name = chosen[i / per_method];
      const double dt = step(i);
      progress.step(fmt::format("{} dt = {:g}", name, dt));
      const RunResult r =
          require(solve(*ball.model, {.name = name, .dt = dt}, {.t_end = t_final, .sample_dt = t_final}),
                  fmt::format("{} (dt = {:g})", name, dt));
      return {ball.error(r, !method_info(name).uses_contact_law), r.stats.rhs_evals};
    });
    if (!results) return;  // another MPI rank: its share is done
    for (std::size_t m = 0; m < chosen.size(); ++m) {
      const std::string& name = chosen[m];
      const std::string reference = method_info(name).uses_contact_law ? "spring" : "rigid";
      std::vector<ConvergencePoint> points;
      std::string rows;
      for (std::size_t i = m * per_method; i < (m + 1) * per_method; ++i) {
        const double dt = step(i), err = (*results)[i][0].get<double>();
        const long rhs = (*results)[i][1].get<long>();
        const double order =
            points.empty() ? std::nan("") : observed_order(points.back().step, points.back().error, dt, err);
        points.push_back({dt, err, rhs});
        errors.add_row({name, reference, dt, err, order, rhs});
        rows += fmt::format("{},{}\n", dt, std::max(err, kFloor));
      }
      orders.add_row({name, reference, fitted_order(points, kFloor, kFitRows), points.back().error});
      figure.add(rows, fmt::format("using 1:2 with linespoints title '{} ({})'", name, reference));
    }
    files.add_table("errors", errors);
    files.add_table("orders", orders);
    render(
        {"errors", figure.data(),
         loglog("dt [s]", "error at t_{final}") + "set key outside right font ',8'\nplot " + figure.plot()},
        files);
    fmt::print("Orders in dt on the bouncing ball (e = 1, k = {:g} N/m, error at t = {:g} s)\n\n{}", k,
               t_final, orders.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("method_orders", argc, argv, program); }
