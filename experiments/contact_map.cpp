// contact_map — the practitioner's map: the restitution and energy error one spring contact costs a
// fixed-step scheme, over the contact's w dt and damping ratio zeta.
// One isolated contact (no gravity, m = 1 kg, entering at V = 2 m/s, above Box2D's 1 m/s restitution
// threshold) on a Kelvin–Voigt spring k = 1e4 N/m (w = 100 rad/s) with zeta from --zetas, whose
// exact restitution is e = exp(-zeta pi / sqrt(1 - zeta^2)) (the rigid methods' e is set to it),
// advanced by explicit Euler (game-euler-spring), semi-implicit Euler (game-symplectic-spring),
// implicit Euler (game-implicit-spring) and Box2D's soft step (soft-step: its own hertz and zeta
// from the law, restitution applied as a velocity target), at w dt from 0.01 to --wdt-max.
// Each point is the worst of --phases entry phases (the floor reached at a fraction (j + 1/2) /
// phases of a step), since the phase moves the result by O(w dt). Reported: the effective
// restitution's relative error e_num / e - 1 and the energy error per contact e_num^2 - e^2 (the
// kinetic energy out over in, less the law's own loss), worst in magnitude over the phases; and
// the map's summary, the largest w dt at which each scheme keeps the restitution within 1 % and
// 10 % (at every smaller grid step too). Under mpirun the (scheme, zeta, w dt) cases go over ranks.
// Outputs in --out (default results/contact_map): map.{csv,md,tex}, steps.{csv,md,tex},
// {explicit,semi_implicit,implicit,soft}.{png,pdf,gp}, meta.json. Exit codes: 0, 1 failure, 2 bad input.
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/law_registry.hpp"
#include "experiment.hpp"
#include "figure.hpp"
#include "process.hpp"
#include "progress.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

using namespace contact;

namespace {

struct Scheme {
  std::string method, file, title;
};
const std::vector<Scheme> kSchemes = {{"game-euler-spring", "explicit", "explicit Euler"},
                                      {"game-symplectic-spring", "semi_implicit", "semi-implicit Euler"},
                                      {"game-implicit-spring", "implicit", "implicit Euler"},
                                      {"soft-step", "soft", "soft step (Box2D)"}};

double restitution_of(double zeta) { return std::exp(-zeta * M_PI / std::sqrt(1 - zeta * zeta)); }

}  // namespace

int program(int argc, char** argv) {
  long points = 16, phases = 8;
  double wdt_max = 4.0;
  std::vector<double> zetas{0, 0.05, 0.2, 0.5};
  Experiment app("contact_map",
                 "Restitution and energy error per spring contact over (w dt, zeta), per scheme.",
                 "results/contact_map");
  app.add("--points", points, "w dt values, log-spaced from 0.01", cli::integer_in(2, 200));
  app.add("--wdt-max", wdt_max, "largest w dt", cli::real_in(0.01, 100, false, true));
  app.add("--phases", phases, "entry phases per point (the worst is reported)", cli::integer_in(1, 64));
  app.add_list("--zetas", zetas, "damping ratios, comma-separated", cli::real_in(0, 0.9, false, false));
  return app.run(argc, argv, [&](OutputSet& files) {
    const double m = 1, V = 2, k = 1e4, w = std::sqrt(k / m);
    std::vector<double> wdts;
    for (long j = 0; j < points; ++j)
      wdts.push_back(0.01 *
                     std::pow(wdt_max / 0.01, static_cast<double>(j) / static_cast<double>(points - 1)));
    const std::size_t per_scheme = zetas.size() * wdts.size();
    Progress progress("contact_map", kSchemes.size() * per_scheme);
    const auto results = app.share(kSchemes.size() * per_scheme, [&](std::size_t i) -> nlohmann::json {
      const Scheme& s = kSchemes[i / per_scheme];
      const double zeta = zetas[i % per_scheme / wdts.size()], wdt = wdts[i % wdts.size()], dt = wdt / w;
      const double e = restitution_of(zeta);
      progress.step(fmt::format("{} zeta = {:g} w dt = {:.3g}", s.method, zeta, wdt));
      double worst_e = 0, worst_energy = 0;  // largest in magnitude over the phases; inf: never let go
      for (long j = 0; j < phases; ++j) {
        const double h0 = (static_cast<double>(j) + 0.5) / static_cast<double>(phases) * V * dt;
        const BallDrop model({m, 0.0, h0, -V, e, make_law("kelvin-voigt", {.k = k, .m = m, .e = e, .v = V})});
        const double t_end = h0 / V + 20 * M_PI / w + 10 * dt;  // the slowest contact ends well before
        const RunResult r =
            solve(model, Method{.name = s.method, .dt = dt}, {.t_end = t_end, .sample_dt = t_end});
        const bool closed = r.ok() && !r.contacts.empty() && r.contacts.front().closed();
        const double e_num =
            closed ? r.contacts.front().restitution() : std::numeric_limits<double>::infinity();
        if (std::abs(e_num / e - 1) > std::abs(worst_e)) worst_e = e_num / e - 1;
        if (std::abs(e_num * e_num - e * e) > std::abs(worst_energy)) worst_energy = e_num * e_num - e * e;
      }
      return {worst_e, worst_energy};
    });
    if (!results) return;  // another MPI rank: its share is done
    Table map({"scheme", "zeta", "target_e", "omega_dt", "dt_s", "restitution_error_rel", "energy_error"});
    Table steps({"scheme", "zeta", "target_e", "omega_dt_1pct", "omega_dt_10pct"});
    steps.set_latex_header(
        {"scheme", "$\\zeta$", "$e$", "$\\omega\\Delta t$, 1\\,\\%", "$\\omega\\Delta t$, 10\\,\\%"});
    for (std::size_t si = 0; si < kSchemes.size(); ++si) {
      Series series;
      for (std::size_t zi = 0; zi < zetas.size(); ++zi) {
        double ok1 = std::nan(""), ok10 = std::nan("");  // largest w dt with every smaller one within
        bool within1 = true, within10 = true;
        std::string rows;
        for (std::size_t wi = 0; wi < wdts.size(); ++wi) {
          const auto& r = (*results)[si * per_scheme + zi * wdts.size() + wi];
          const double rel = r[0].get<double>(), energy = r[1].get<double>();
          map.add_row({kSchemes[si].method, zetas[zi], restitution_of(zetas[zi]), wdts[wi], wdts[wi] / w, rel,
                       energy});
          within1 = within1 && std::abs(rel) <= 0.01;
          within10 = within10 && std::abs(rel) <= 0.1;
          if (within1) ok1 = wdts[wi];
          if (within10) ok10 = wdts[wi];
          if (std::isfinite(rel)) rows += fmt::format("{},{}\n", wdts[wi], std::max(std::abs(rel), 1e-16));
        }
        steps.add_row({kSchemes[si].method, zetas[zi], restitution_of(zetas[zi]), ok1, ok10});
        series.add(rows, fmt::format("using 1:2 with linespoints {} title 'zeta = {:g}'", series_style(zi),
                                     zetas[zi]));
      }
      render({kSchemes[si].file, series.data(),
              loglog("omega dt", "|e_{num} / e - 1|, worst entry phase") + "set key top left\nset title '" +
                  kSchemes[si].title + "'\nset yrange [1e-6:10]\nplot " + series.plot() +
                  ", 0.01 with lines dt 3 lc rgb 'gray50' title '1 %'"},
             files);
    }
    files.add_table("map", map);
    files.add_table("steps", steps);
    fmt::print("The largest w dt per scheme keeping the restitution within 1 % and 10 %\n\n{}",
               steps.to_markdown(3));
  });
}

int main(int argc, char** argv) { return contact::guarded_main("contact_map", argc, argv, program); }
