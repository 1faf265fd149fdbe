#pragma once
// A Result as plain Python values and back, so that pickle (and with it multiprocessing and
// concurrent.futures.ProcessPoolExecutor, a sweep's usual way to use more cores) can carry one
// between processes. Exact: every double travels as a Python float.
#include "contact_ode/integrators/run_result.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <stdexcept>
#include <tuple>
#include <vector>

namespace contact::python {

namespace py = pybind11;

// The layout's version, first in the state: a pickle from another layout is refused by name.
inline constexpr int kResultStateVersion = 1;

inline py::tuple result_state(const RunResult& r) {
  std::vector<std::tuple<double, std::vector<double>, double, double>> samples;
  samples.reserve(r.samples.size());
  for (const Sample& s : r.samples)
    samples.emplace_back(s.t, std::vector<double>(s.y.data(), s.y.data() + s.y.size()), s.energy,
                         s.dissipated);
  std::vector<std::tuple<std::size_t, double, double, double, double, double>> contacts;
  for (const ContactRecord& c : r.contacts)
    contacts.emplace_back(c.contact, c.t_begin, c.t_end, c.max_penetration, c.v_in, c.v_out);
  std::vector<std::tuple<std::size_t, double, double, double, double>> apexes;
  for (const Apex& a : r.apexes) apexes.emplace_back(a.contact, a.t, a.gap, a.energy, a.dissipated);
  std::vector<std::tuple<bool, std::size_t, long, double>> notifications;
  for (const CollisionEvent& n : r.notifications)
    notifications.emplace_back(n.kind == CollisionEvent::Kind::Begin, n.contact, n.step, n.t);
  const SolverStats& s = r.stats;
  const auto stats =
      std::make_tuple(s.steps, s.failed_steps, s.rhs_evals, s.jac_evals, s.newton_iters, s.linear_setups,
                      s.linear_iters, s.root_evals, s.events, s.restarts, s.wall_time_s, s.setup_cpu_s);
  return py::make_tuple(kResultStateVersion, r.method, r.state_labels, r.energy0, samples, contacts, apexes,
                        notifications, stats, r.status, r.t_reached, r.message);
}

inline RunResult result_from_state(const py::tuple& state) {
  if (state.size() != 12 || state[0].cast<int>() != kResultStateVersion)
    throw std::invalid_argument(
        "a pickled contact_ode.Result of another layout; pickle it again with this module");
  RunResult r;
  r.method = state[1].cast<std::string>();
  r.state_labels = state[2].cast<std::vector<std::string>>();
  r.energy0 = state[3].cast<double>();
  for (const auto& [t, y, energy, dissipated] :
       state[4].cast<std::vector<std::tuple<double, std::vector<double>, double, double>>>()) {
    if (y.size() != r.state_labels.size())  // Result.y reads state_labels.size() values of each
      throw std::invalid_argument("a pickled contact_ode.Result whose samples do not match its state labels");
    r.samples.push_back(
        {t, Eigen::Map<const Vector>(y.data(), static_cast<Eigen::Index>(y.size())), energy, dissipated});
  }
  for (const auto& [contact, t_begin, t_end, pen, v_in, v_out] :
       state[5].cast<std::vector<std::tuple<std::size_t, double, double, double, double, double>>>())
    r.contacts.push_back({contact, t_begin, t_end, pen, v_in, v_out});
  for (const auto& [contact, t, gap, energy, dissipated] :
       state[6].cast<std::vector<std::tuple<std::size_t, double, double, double, double>>>())
    r.apexes.push_back({contact, t, gap, energy, dissipated});
  for (const auto& [begin, contact, step, t] :
       state[7].cast<std::vector<std::tuple<bool, std::size_t, long, double>>>())
    r.notifications.push_back(
        {begin ? CollisionEvent::Kind::Begin : CollisionEvent::Kind::End, contact, step, t});
  SolverStats& s = r.stats;
  std::tie(s.steps, s.failed_steps, s.rhs_evals, s.jac_evals, s.newton_iters, s.linear_setups, s.linear_iters,
           s.root_evals, s.events, s.restarts, s.wall_time_s, s.setup_cpu_s) =
      state[8].cast<std::tuple<long, long, long, long, long, long, long, long, long, long, double, double>>();
  r.status = state[9].cast<Status>();
  r.t_reached = state[10].cast<double>();
  r.message = state[11].cast<std::string>();
  return r;
}

}  // namespace contact::python
