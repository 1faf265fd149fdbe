// newton_cradle — where the striker's momentum and energy go in a row of --balls equal balls of the 1D chain
// (models/ball_chain.hpp): steel, m = 0.1 kg, radius 14.5 mm, the striker at 1 m/s from 1 cm away, the others
// at rest --spacings apart (0 = touching). Methods: event (Newton's law, e = 1, CVODE flight); game
// (semi-implicit Euler, projection + impulse); Hooke springs k = --k (penalty-linear) and Hertz's, K = (4/3)
// E* sqrt(R*) for steel (penalty-hertz), under CVODE BDF at rtol 1e-10; the engines' moreau-jean,
// sequential-impulses, soft-step (its restitution threshold clear of the strike), xpbd and
// game-implicit-spring, at the fixed step --dt. Reported, every contact open again: each ball's velocity, the
// last ball's share of the initial kinetic energy and the energy error. Sequential impulses give the textbook
// answer (the last ball leaves at 1 m/s, the rest stop) at any spacing; touching linear springs disperse the
// pulse, Hertz's come close; a gap beyond the compression makes binary, exact exchanges. Outputs in --out
// (default results/newton_cradle): velocities.{csv,md,tex}, final_velocities and energy_share figures (.png,
// .pdf, .gp), meta.json; mpirun deals the runs over ranks. Exit codes: 0, 1 failure, 2 bad input.
#include "contact_ode/analysis/metrics.hpp"
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_chain.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "output.hpp"
#include "problems.hpp"
#include "process.hpp"
#include "progress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace contact;

namespace {
constexpr double kZeroSpacing = 1e-9;  // touching balls, drawn here on the log axis [m]
}  // namespace

int program(int argc, char** argv) {
  double k = 1e6, dt = 1e-6;
  long balls = 5;
  std::vector<double> spacings{0.0, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3};
  Experiment app("newton_cradle",
                 "Newton's cradle: final velocities and the last ball's energy share by every method.",
                 "results/newton_cradle");
  // A cradle, not a chain (span and step grow with it: 100 balls 4.5 min; 1000, once allowed, 7 h).
  app.add("--balls", balls, "balls in the row (the cost grows as balls^2: 100 take minutes)",
          cli::integer_in(2, 100));
  app.add("--k", k, "linear penalty stiffness [N/m]", cli::positive());
  app.add("--dt", dt, "game step [s]", cli::positive());
  app.add_list("--spacings", spacings, "gaps between the resting balls [m], comma-separated",
               cli::real_in(0, 1, false, false));  // 34 diameters; 1e308 m overflowed a run's span
  return app.run(argc, argv, [&](OutputSet& files) {
    const double m = 0.1, radius = 0.0145, v0 = 1.0, approach = 0.01;
    const double hertz_k = hertz_stiffness(radius / 2, effective_modulus(200e9, 0.3, 200e9, 0.3));
    const std::vector<std::string> methods = {"event",         "game",        "penalty-linear",
                                              "penalty-hertz", "moreau-jean", "sequential-impulses",
                                              "soft-step",     "xpbd",        "game-implicit-spring"};
    const auto n = static_cast<std::size_t>(balls);
    const auto row_length = static_cast<double>(balls);
    // The longest binary contact (effective mass m/2, at the striker's speed): the pulse needs a few
    // of them per ball to cross the row, so 10 per ball leaves every contact open again at the end.
    const double contact_time = std::max(hooke_contact(m / 2, k, v0, 0.0).duration,
                                         power_law_contact(m / 2, hertz_k, 1.5, v0).duration);
    std::vector<std::string> columns = {"method", "spacing_m"};
    for (std::size_t b = 0; b < n; ++b) columns.push_back(fmt::format("v{}_mps", b));
    columns.insert(columns.end(), {"last_ball_energy_share", "energy_error_rel", "contacts", "rhs_evals"});
    Table table(columns);
    // The rows' labels name the law for the penalty runs; the registry's methods run them.
    std::map<std::string, std::string> runs_as = {{"event", "event-ode"}, {"game", "game-symplectic"}};
    runs_as["penalty-linear"] = runs_as["penalty-hertz"] = "penalty";
    // Run i: method i / per_method at spacing i % per_method, over the pulse's time to the last ball
    // and ten of the longest contacts per ball to cross the row.
    const std::size_t per_method = spacings.size();
    std::vector<PlannedRun> planned;
    for (const std::string& method : methods)
      for (const double spacing : spacings) {
        Method mt = clear_of_restitution_threshold(
            {.name = runs_as.contains(method) ? runs_as.at(method) : method, .dt = dt}, v0);
        if (mt.name == "penalty") mt.integrator = {.rtol = 1e-10, .atol = 1e-14, .max_steps = 10000000};
        planned.push_back({fmt::format("{} (spacing {:g} m)", method, spacing), mt,
                           (approach + row_length * spacing) / v0 + 10.0 * row_length * contact_time});
      }
    refuse_dt_beyond_work_limit(planned);
    Progress progress("newton_cradle", planned.size());
    const auto results = app.share(planned.size(), [&](std::size_t i) -> nlohmann::json {
      const std::string& method = methods[i / per_method];
      const PlannedRun& run = planned[i];
      progress.step(run.what);
      const BallChain chain({.n = n,
                             .m = m,
                             .v0 = v0,
                             .approach = approach,
                             .spacing = spacings[i % per_method],
                             .law = method == "penalty-hertz" ? ContactLaw{HuntCrossley{hertz_k, 1.5, 0.0}}
                                                              : ContactLaw{Hooke{k}}});
      const RunResult r =
          require(solve(chain, run.method, {.t_end = run.t_end, .sample_dt = run.t_end}), run.what);
      // Final velocities: every contact open again, or balls left touching at one velocity (a game
      // step longer than the gap), or, under a time-stepping method, clumped (a soft step's to 1e-8).
      const Vector& y = r.samples.back().y;
      const auto v = [&y](std::size_t b) { return y[static_cast<Eigen::Index>(2 * b + 1)]; };
      const bool clumps = method_info(run.method.name).family == "time-stepping";
      for (const ContactRecord& c : r.contacts)
        if (!c.closed() && !clumps && v(c.contact) != v(c.contact + 1))
          throw std::runtime_error(
              fmt::format("{}: a contact is still open at t = {:g} s", run.what, run.t_end));
      const double last = v(n - 1);
      std::vector<Table::Cell> row = {method, spacings[i % per_method]};
      for (std::size_t b = 0; b < n; ++b) row.emplace_back(v(b));
      row.insert(row.end(), {0.5 * m * last * last / (0.5 * m * v0 * v0), 0.0 - energy_drifts(r).back(),
                             static_cast<long>(r.contacts.size()), r.stats.rhs_evals});
      return row_to_json(row);
    });
    if (!results) return;  // another MPI rank: its share is done
    Series share_figure, velocities;
    std::map<std::string, std::string> shares;  // method -> "spacing,share" lines
    for (std::size_t i = 0; i < results->size(); ++i) {
      const auto row = row_from_json((*results)[i]);  // ball b's velocity: column 2 + b; share: 2 + n
      const std::string& method = methods[i / per_method];
      const double spacing = spacings[i % per_method];
      table.add_row(row);
      shares[method] += fmt::format("{},{}\n", std::max(spacing, kZeroSpacing), std::get<double>(row[2 + n]));
      if (spacing == spacings.front()) {
        std::string rows;
        for (std::size_t b = 0; b < n; ++b) rows += fmt::format("{},{}\n", b, std::get<double>(row[2 + b]));
        // Bars of the methods side by side around each ball's index.
        const double offset =
            0.15 * (static_cast<double>(i / per_method) - 0.5 * static_cast<double>(methods.size() - 1));
        velocities.add(rows, fmt::format("using ($1 + {}):2 with impulses lw 6 title '{}'", offset, method));
      }
    }
    for (const auto& method : methods)
      share_figure.add(shares[method], fmt::format("using 1:2 with linespoints title '{}'", method));
    files.add_table("velocities", table);
    render({"final_velocities", velocities.data(),
            fmt::format("set xlabel 'ball'\nset ylabel 'final velocity [m/s]'\nset xrange [-0.5:{}]\n"
                        "set xtics 1\nset grid\nset key top left\nplot {}",
                        row_length - 0.5, velocities.plot())},
           files);
    render(
        {"energy_share", share_figure.data(),
         fmt::format("set logscale x\nset format x '10^{{%L}}'\nset xlabel 'spacing [m] (0 drawn at {:g})'\n"
                     "set ylabel 'last ball energy / initial'\nset key bottom right\nset grid\nplot {}",
                     kZeroSpacing, share_figure.plot())},
        files);
    fmt::print("Newton's cradle: {} balls at {:g} m/s (k = {:g} N/m, Hertz K = {:.4g} N/m^1.5)\n\n{}", n, v0,
               k, hertz_k, table.to_markdown());
  });
}

int main(int argc, char** argv) { return contact::guarded_main("newton_cradle", argc, argv, program); }
