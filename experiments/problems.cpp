#include "problems.hpp"

#include "contact_ode/analysis/cpu_time.hpp"
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_chain.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "experiment.hpp"
#include "sweep_setting.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <stdexcept>

namespace contact {

Problem ball_problem(double k, double t_end, double h0) {
  const double m = 1.0, g = 9.81, V = std::sqrt(2 * g * h0);
  auto error = [=](const RunResult& r, bool rigid) {
    const Vector& y = r.samples.back().y;
    const BallState ref =
        rigid ? rigid_ball_state(h0, 0.0, g, 1.0, t_end) : hooke_ball_state(m, k, h0, 0.0, g, t_end);
    return std::max(std::abs(y[0] - ref.x) / h0, std::abs(y[1] - ref.v) / V);
  };
  return {"ball",
          std::make_shared<BallDrop>(BallDropParams{m, g, h0, 0.0, 1.0, Hooke{k}}),
          t_end,
          hooke_contact(m, k, V, g).duration,
          fmt::format("--k: value '{}' makes", k),
          error};
}

ErrorSpread error_over(const std::vector<Problem>& problems,
                       const std::function<RunResult(const Problem&)>& solve_one) {
  ErrorSpread out;
  const double cpu0 = cpu_seconds();
  std::size_t runs = 0;
  for (const auto& problem : problems) {
    const RunResult r = solve_one(problem);
    ++runs;
    out.rhs += static_cast<double>(r.stats.rhs_evals);
    if (!r.ok()) {
      out.status = to_string(r.status);
      out.failure = failure_text(r);
      out.max = out.rms = std::nan("");
      break;
    }
    const double err = problem.error(r, false);
    out.max = std::max(out.max, err);
    out.rms += err * err;
  }
  const double n = static_cast<double>(runs);
  out.rms = std::sqrt(out.rms / n);
  out.rhs /= n;
  out.cpu_s = (cpu_seconds() - cpu0) / n;
  return out;
}

std::vector<ErrorSpread> errors_down_to(const std::vector<double>& steps, double floor,
                                        const std::function<ErrorSpread(double)>& at_step) {
  std::vector<ErrorSpread> rows;
  for (const double step : steps) {
    rows.push_back(at_step(step));
    if (rows.back().ok() && rows.back().max < floor) break;
  }
  return rows;
}

bool report(const ErrorSpread& r, const std::string& what) {
  if (!r.ok()) std::cerr << what << ": " << r.failure << "\n";
  return r.ok();
}

std::vector<Problem> ball_problems_over_heights(double k, double t_end, std::size_t count) {
  const double golden = (std::sqrt(5.0) - 1) / 2;
  std::vector<Problem> drops;
  for (std::size_t j = 0; j < count; ++j)
    drops.push_back(
        ball_problem(k, t_end, 1.0 + 0.25 * std::fmod((static_cast<double>(j) + 0.5) * golden, 1.0)));
  return drops;
}

Problem chain_problem(long balls, double k) {
  const BallChainParams p{.n = static_cast<std::size_t>(balls), .law = Hooke{k}};
  auto chain = std::make_shared<BallChain>(p);
  const double contact = hooke_contact(p.m / 2, k, p.v0, 0.0).duration;
  const double t_end = p.approach / p.v0 + 3.0 * static_cast<double>(p.n) * contact;
  Method reference{.name = "penalty"};
  reference.integrator.rtol = 1e-12;
  reference.integrator.atol = 1e-14;
  reference.integrator.max_steps = 10000000;
  const Vector spring =
      require(solve(*chain, reference, {.t_end = t_end, .sample_dt = t_end}), "chain reference")
          .samples.back()
          .y;
  auto error = [=](const RunResult& r, bool rigid) {
    const Vector& y = r.samples.back().y;
    double err = 0;
    for (std::size_t b = 0; b < p.n; ++b) {
      const auto i = static_cast<Eigen::Index>(2 * b + 1);
      const double ref = rigid ? (b + 1 == p.n ? p.v0 : 0.0) : spring[i];
      err = std::max(err, std::abs(y[i] - ref) / p.v0);
    }
    return err;
  };
  return {"chain", chain, t_end, contact, fmt::format("--chain-k, --balls: values '{}', '{}' make", k, balls),
          error};
}

namespace {

// The sweep's run at `value` (a step or a tolerance); the exact integrator has neither.
Method method_with(const std::string& method, const std::string& integrator, double value) {
  Method m{.name = method};
  m.integrator.method = integrator;
  m.integrator.max_steps = kSweepMaxSteps;
  const IntegratorInfo& info = integrator_info(integrator);
  if (!is_exact(info)) m.integrator = with_setting(m.integrator, !info.adaptive, value);
  return m;
}

}  // namespace

std::vector<WorkJob> work_precision_jobs(const std::vector<Problem>& problems,
                                         const std::vector<std::string>& integrators,
                                         const std::vector<double>& tols, long halvings) {
  std::vector<WorkJob> jobs;
  for (const Problem& pr : problems) {
    // The largest fixed step is 1/16 of a contact (w dt = pi/16), halved `halvings` times.
    const auto dts = halved_steps("--halvings", pr.contact_duration / 16, halvings, 0, pr.t_end,
                                  pr.set_by + " the " + pr.name + "'s largest step (1/16 of a contact)");
    for (const auto& name : integrators) {
      if (is_exact(integrator_info(name))) {  // no setting: one run
        jobs.push_back({&pr, "penalty", name, "exact", 0.0, method_with("penalty", name, 0.0)});
        continue;
      }
      const bool adaptive = integrator_info(name).adaptive;
      for (double v : adaptive ? tols : dts)
        jobs.push_back({&pr, "penalty", name, adaptive ? "rtol" : "dt", v, method_with("penalty", name, v)});
    }
    for (const auto& [paradigm, method] : {std::pair<std::string, std::string>{"game", "game-symplectic"},
                                           {"game-spring", "game-symplectic-spring"}})
      for (double dt : dts)
        jobs.push_back({&pr, paradigm, "semi-implicit-euler", "dt", dt, Method{.name = method, .dt = dt}});
    for (const std::string name : {"cvode-bdf", "gsl-rk8pd"})
      for (double tol : tols)
        jobs.push_back({&pr, "event", name, "rtol", tol, method_with("event-ode", name, tol)});
    if (pr.name == "ball")
      jobs.push_back({&pr, "event", "exact-flight", "exact", 0.0, Method{.name = "event-exact"}});
  }
  return jobs;
}

std::vector<std::string> work_panels(const std::string& paradigm, const std::string& integrator) {
  if (paradigm == "scipy") return {"peers"};
  if (paradigm != "penalty") return {"paradigms"};
  std::vector<std::string> panels{
      integrator_info(integrator).implicit || integrator_info(integrator).variable_order ? "implicit"
                                                                                         : "explicit"};
  if (integrator == "cvode-bdf") panels.push_back("paradigms");
  if (integrator == "cvode-bdf" || integrator == "cvode-adams" || integrator == "gsl-rkf45")
    panels.push_back("peers");
  return panels;
}

PanelAxis work_panel_axis(const std::string& problem, const std::string& panel) {
  if (panel == "paradigms") return {true, "error against the rigid body"};
  return {false, problem == "ball" ? "error against the spring solution (closed form)"
                                   : "error against the spring chain at rtol 10^{-12}"};
}

double first_apex_error(const BallDropParams& p, const RunResult& r) {
  if (!r.ok() || r.apexes.empty()) return NAN;
  return std::abs(r.apexes.front().gap - RigidBounces(p.h0, p.v0, p.g, p.e).apex_height(1));
}

double first_bounce_window(const BallDropParams& p, double at_least) {
  if (!(p.g > 0)) return at_least;  // no rigid flight to the floor to bound it by
  const LinearLaw law = linear_law(p.law);
  const double zeta = law.c / (2 * std::sqrt(law.k * p.m));
  const double V = impact_speed(p.h0, p.v0, p.g), fall = RigidBounces(p.h0, p.v0, p.g, p.e).T1;
  const double contact = hooke_contact(p.m, law.k, V, p.g).duration / std::sqrt(1 - zeta * zeta);
  const double window = fall + 1.25 * contact + V / p.g + 0.05;
  return std::isfinite(window) ? std::max(at_least, window) : at_least;
}

bool held_for_good(const RunResult& r, const BallDropParams& p) {
  if (r.contacts.empty() || r.contacts.back().closed() || r.samples.empty()) return false;
  const LinearLaw law = linear_law(p.law);
  const double s = p.m * p.g / law.k, delta = -r.samples.back().y[0], rate = -r.samples.back().y[1];
  const double energy = 0.5 * p.m * rate * rate + 0.5 * law.k * (delta - s) * (delta - s);
  // At energy E, u = delta - s reaches at most sqrt(2 E / k), and k u + c u' (Cauchy–Schwarz)
  // sqrt(2 E (k + c^2 / m)).
  const double reach = releases_while_overlapping(p.law) ? law.k + law.c * law.c / p.m : law.k;
  return std::sqrt(2 * energy * reach) < law.k * s;
}

double damped_period(const BallDropParams& p) {
  const LinearLaw law = linear_law(p.law);
  return 2 * std::numbers::pi / std::sqrt(law.k / p.m - std::pow(law.c / (2 * p.m), 2));
}

std::string first_bounce(const RunResult& r, const BallDropParams& p, const std::string& what,
                         std::string_view remedy) {
  const double t_end = r.samples.empty() ? r.t_reached : r.samples.back().t;
  if (!r.contacts.empty() && r.contacts.front().closed() && !r.apexes.empty()) return "bounced";
  const double k = linear_law(p.law).k;
  // A law with no force on the rate gives back all the energy it takes: it cannot hold the ball,
  // whatever its k, and a run in which it did was held by the integrator's error.
  if (dforce_drate(p.law, 1.0, 0.0) == 0.0)
    throw std::runtime_error(fmt::format(
        "{}: no first apex by t = {:.3g} s: an undamped spring gives back the energy it takes{}, so "
        "the integrator's error held the ball on it{}",
        what, t_end,
        std::isfinite(k) ? fmt::format(" (its contact lasts {:.3g} s)",
                                       hooke_contact(p.m, k, impact_speed(p.h0, p.v0, p.g), p.g).duration)
                         : std::string(),
        remedy));
  if (r.contacts.size() == 1 && held_for_good(r, p)) return "held";
  throw std::runtime_error(fmt::format(
      "{}: no complete first bounce by t = {:.3g} s{}", what, t_end,
      std::isfinite(k)
          ? fmt::format(" (a soft damped spring can hold the ball: its static sag m g / k is {:.3g} "
                        "m against h0 = {:g} m)",
                        p.m * p.g / k, p.h0)
          : std::string()));
}

std::vector<ScoredScene> engine_scenes(double k) {
  auto velocities = [](std::function<double(Eigen::Index, Eigen::Index)> exact) {
    return [exact](const RunResult& r, bool) {
      const Vector& y = r.samples.back().y;
      const Eigen::Index n = y.size() / 2;
      double err = 0;
      for (Eigen::Index b = 0; b < n; ++b) err = std::max(err, std::abs(y[2 * b + 1] - exact(b, n)));
      return err;
    };
  };
  const auto last_ball = velocities([](Eigen::Index b, Eigen::Index n) { return b + 1 == n ? 1.0 : 0.0; });
  const double m = 0.1, g = 9.81, n = 4, e_drop = 0.8, e_pair = 0.8;
  const BallDropParams drop{.m = 1.0, .g = g, .h0 = 1.0, .v0 = 0.0, .e = e_drop};
  return {{"drop",
           "ball-drop",
           "|first apex - e^2 h0| [m]",
           {{"e", drop.e}, {"g", drop.g}, {"h0", drop.h0}, {"v0", drop.v0}, {"m", drop.m}, {"k", k}},
           3.0,
           RigidBounces(drop.h0, drop.v0, drop.g, drop.e).apex_time(1),
           [drop](const RunResult& r, bool) { return first_apex_error(drop, r); }},
          {"head-on",
           "ball-chain",
           "max |v - exact| [m/s]",
           {{"n", 2}, {"e", e_pair}, {"v0", 1.0}, {"approach", 1e-3}, {"k", k}},
           0.05,
           NAN,
           // Equal masses, striker at 1 m/s: (1 - e) / 2 and (1 + e) / 2.
           velocities([e_pair](Eigen::Index b, Eigen::Index) {
             return b == 0 ? (1 - e_pair) / 2 : (1 + e_pair) / 2;
           })},
          {"cradle-1mm",
           "ball-chain",
           "max |v - sequential| [m/s]",
           {{"n", 5}, {"e", 1}, {"v0", 1.0}, {"spacing", 1e-3}, {"k", k}},
           0.05,
           NAN,
           last_ball},
          {"cradle-0",
           "ball-chain",
           "max |v - sequential| [m/s]",
           {{"n", 5}, {"e", 1}, {"v0", 1.0}, {"spacing", 0}, {"k", k}},
           0.05,
           NAN,
           last_ball},
          {"stack",
           "ball-stack",
           "|top sink - exact| [m]",
           {{"n", n}, {"e", 0.5}, {"m", m}, {"g", g}, {"k", k}},
           2.0,
           NAN,
           [=](const RunResult& r, bool springs) {
             const Vector& y = r.samples.back().y;
             return std::abs(-y[y.size() - 2] - (springs ? m * g * n * (n + 1) / (2 * k) : 0.0));
           }}};
}

Method clear_of_restitution_threshold(Method m, double v0) {
  if (m.name == "soft-step" && std::isnan(m.restitution_threshold)) m.restitution_threshold = 0.5 * v0;
  return m;
}

}  // namespace contact
