// contact_laws — the restitution each contact law achieves against the one it was tuned for.
// One isolated contact (no gravity, mass --m, impact speed --v) per law and target e, integrated
// to rtol 1e-10 (analysis/contact_measurement.hpp). Laws: Kelvin–Voigt unclamped and clamped (damping
// from the linear-dashpot formula), and the Hunt–Crossley family F = K delta^n (1 + chi delta_dot),
// n = 1 and 3/2, with the damping rules of Hunt–Crossley, Lankarani–Nikravesh, Flores, Gonthier and the
// exact one.
// K is chosen so that the undamped contact would penetrate --depth; the restitution does not
// depend on K or V for these laws (dimensional analysis: e depends on chi V and n only).
// Outputs in --out (default results/contact_laws): restitution.{csv,md,tex},
// restitution.{png,pdf,gp}, meta.json. Exit codes: 0, 1 simulation failure, 2 bad input.
#include "contact_ode/analysis/contact_measurement.hpp"
#include "contact_ode/analysis/table.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "output.hpp"
#include "process.hpp"
#include "progress.hpp"

#include <fmt/format.h>

#include <cfloat>
#include <chrono>
#include <cmath>
#include <iostream>

using namespace contact;

namespace {

struct LawCase {
  std::string label;
  std::function<ContactLaw(double e)> make;
};

}  // namespace

int program(int argc, char** argv) {
  double m = 1.0, v = 1.0, depth = 1e-3;
  long points = 10;
  Experiment app("contact_laws", "Restitution each contact law achieves against the target it was tuned for.",
                 "results/contact_laws");
  app.add("--m", m, "mass [kg]", cli::positive());
  app.add("--v", v, "impact speed [m/s]", cli::positive());
  app.add("--depth", depth, "undamped penetration the stiffness is chosen for [m]", cli::positive());
  app.add("--points", points, "target restitutions, evenly spaced in (0, 1]", cli::integer_in(2, 1000));
  return app.run(argc, argv, [&](OutputSet& files) {
    std::vector<LawCase> cases;
    const double k_lin = m * v * v / (depth * depth);  // Hooke: V sqrt(m/k) = depth
    // Each option is in range, but together they can give a stiffness that rounds to 0 or inf
    // (--v 1e-300: K = 0), which the law refused in its own terms, naming none of them.
    for (const double n : {1.0, 1.5})
      if (const double K = (n + 1) * m * v * v / (2 * std::pow(depth, n + 1));
          !(K >= DBL_MIN && K <= DBL_MAX))
        throw std::invalid_argument(fmt::format(
            "--m, --v, --depth: values '{:g}', '{:g}', '{:g}' give a contact stiffness (n + 1) m v^2 / (2 "
            "depth^(n + 1)) = {:g} at n = {:g}, outside the doubles' normal range [{:g}, {:g}]",
            m, v, depth, K, n, DBL_MIN, DBL_MAX));
    cases.push_back({"kelvin-voigt",
                     [&](double e) { return ContactLaw{kelvin_voigt_for_restitution(k_lin, m, e, false)}; }});
    cases.push_back({"kelvin-voigt-clamped",
                     [&](double e) { return ContactLaw{kelvin_voigt_for_restitution(k_lin, m, e, true)}; }});
    for (double n : {1.0, 1.5}) {
      const double K = (n + 1) * m * v * v / (2 * std::pow(depth, n + 1));  // power law: depth
      for (const DampingRule rule : kDampingRules)
        cases.push_back({fmt::format("{} n={}", to_string(rule), n == 1.0 ? "1" : "3/2"), [=](double e) {
                           return ContactLaw{HuntCrossley{K, n, damping_factor(rule, e, v)}};
                         }});
    }

    Table table({"law", "target_e", "achieved_e", "miss"});
    Progress progress("contact_laws", cases.size() * static_cast<std::size_t>(points));
    std::string data = "law,target_e,achieved_e\n";
    for (const auto& c : cases) {
      for (long j = 1; j <= points; ++j) {
        const double e = static_cast<double>(j) / static_cast<double>(points);
        progress.step(fmt::format("{} e = {:g}", c.label, e));
        double achieved;
        try {
          achieved = measure_isolated_contact(c.make(e), m, v).exit_speed / v;
        } catch (const std::exception& ex) {
          throw std::runtime_error(fmt::format("{} at e = {:g}: {}", c.label, e, ex.what()));
        }
        table.add_row({c.label, e, achieved, achieved - e});
      }
    }
    // The figure: one curve per law, blocks separated by blank lines for gnuplot's index.
    std::string blocks;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      for (long j = 0; j < points; ++j) {
        const auto& row = table.rows()[i * static_cast<std::size_t>(points) + static_cast<std::size_t>(j)];
        blocks +=
            fmt::format("{},{},{}\n", cases[i].label, std::get<double>(row[1]), std::get<double>(row[2]));
      }
      blocks += "\n\n";
    }
    std::string plot =
        "set xlabel 'target restitution'\nset ylabel 'achieved restitution'\nset key right bottom\n"
        "set grid\nset xrange [0:1]\nset yrange [0:1.05]\nplot x title 'target' with lines dashtype 2 lc rgb "
        "'black'";
    for (std::size_t i = 0; i < cases.size(); ++i)
      plot += fmt::format(", 'data.csv' index {} using 2:3 with linespoints title '{}'", i, cases[i].label);
    files.add_table("restitution", table);
    render({"restitution", blocks, plot}, files);
    fmt::print("Restitution achieved against the target (m = {:g} kg, v = {:g} m/s, no gravity)\n\n{}", m, v,
               table.to_markdown());
  });
}

int main(int argc, char** argv) { return contact::guarded_main("contact_laws", argc, argv, program); }
