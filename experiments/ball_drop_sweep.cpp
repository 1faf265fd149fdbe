// ball_drop --sweep: every stiffness-dependent method of the ball drop for k from --k-min to
// --k-max, beside the closed forms (sweep.{csv,md,tex}, penetration.{png,pdf,gp}).
#include "ball_drop_setup.hpp"
#include "contact_ode/analysis/fit.hpp"
#include "contact_ode/analysis/run_tables.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "progress.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

namespace contact {

void run_sweep(const BallDropOptions& o, Experiment& app, OutputSet& out) {
  const std::vector<double> ks = log_grid(o.k_min, o.k_max, o.per_decade);

  std::vector<std::string> columns{"k_N_per_m", "method", "omega_dt", "closed_form_penetration_m",
                                   "closed_form_duration_s"};
  columns.insert(columns.end(), metric_columns().begin(), metric_columns().end());
  Table sweep(columns);
  std::vector<std::pair<double, MethodInfo>> runs;
  for (double k : ks)
    for (const auto& name : chosen_methods(o))
      if (method_info(name).uses_contact_law) runs.emplace_back(k, method_info(name));
  for (const auto& name : chosen_methods(o))
    if (!method_info(name).uses_contact_law) runs.emplace_back(std::nan(""), method_info(name));

  Progress progress("ball_drop sweep", runs.size());
  const auto results = app.share(runs.size(), [&](std::size_t i) -> nlohmann::json {
    const auto& [k, m] = runs[i];
    progress.step(fmt::format("k = {:g}, {}", k, m.name));
    const RunResult r = run_ball(o, m.name, std::isnan(k) ? o.k : k);
    // A sweep charts where methods break, so a failed run is a row, not the end of the sweep;
    // but it is said, on stderr, with its status, time and message.
    report(r, fmt::format("ball_drop: sweep: k = {:g}, {}", k, m.name));
    const bool game = m.fixed_step;
    const double nan = std::nan("");  // k NaN: a method without a spring ("any" k), no closed form
    const SpringContact ref = std::isnan(k) ? SpringContact{nan, nan, nan} : closed_form_contact(o, k);
    std::vector<Table::Cell> row{std::isnan(k) ? Table::Cell(std::string("any")) : Table::Cell(k), m.name,
                                 game && !std::isnan(k) ? std::sqrt(k / o.m) * o.dt : std::nan(""),
                                 ref.max_penetration, ref.duration};
    for (auto& c : metric_cells(r)) row.push_back(std::move(c));
    const bool first = !std::isnan(k) && !r.contacts.empty();
    return {
        {"row", row_to_json(row)},
        {"penetration",
         first ? fmt::format("{},{},{}\n", k, r.contacts.front().max_penetration, ref.max_penetration) : ""}};
  });
  if (!results) return;                            // another MPI rank: its share is done
  std::map<std::string, std::string> penetration;  // method -> "k,first penetration,closed form" lines
  for (std::size_t i = 0; i < runs.size(); ++i) {
    sweep.add_row(row_from_json((*results)[i].at("row")));
    const auto line = (*results)[i].at("penetration").get<std::string>();
    if (!line.empty()) penetration[runs[i].second.name] += line;
  }
  Series series;
  for (const auto& [name, rows] : penetration)
    series.add(rows, fmt::format("using 1:2 with points title '{}'", name));
  if (!series.empty())
    render({"penetration", series.data(),
            "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\nset xlabel 'k [N/m]'\n"
            "set ylabel 'first penetration [m]'\nset key bottom left\nset grid\nplot " +
                series.plot() + ", 'data.csv' index 0 using 1:3 with lines lc black title 'closed form'"},
           out);
  fmt::print(
      "Ball drop, k sweep: law {}, e = {:g}, dt = {:g} s, rtol = {:g}, atol = {:g}, t_end = {:g} s\n\n",
      o.law, o.e, o.dt, o.rtol, scaled_atol(o), o.t_end);
  fmt::print("{}\n{}", sweep.to_markdown(), ball_references(o));
  out.add_table("sweep", sweep);
}

}  // namespace contact
