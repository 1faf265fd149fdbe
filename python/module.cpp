// contact_ode for Python: the registries, solve() and the closed forms, on the C++ library itself.
//   import contact_ode as co
//   r = co.solve("ball-drop", "event-exact", h0=2.0, e=0.8, t_end=3.0)
//   r.t, r.y, r.energy            NumPy arrays, one row per sample
//   r.contacts["max_penetration"] one NumPy array per column of the contact log
// Keyword options are the scene's parameters (co.scenes()), the method's settings (dt, rtol,
// atol, integrator, linear_solver, iterations, ...; co.methods() lists what each reads, and a
// setting the method ignores raises a UserWarning), the span (t_end, sample_dt) and the record
// limit (max_records, as ball_drop's --max-records); any other
// name, and any value out of range, raises ValueError naming it. A run that fails raises
// co.SolverError with .status, .t_reached, .solver_message and the partial .result; Ctrl-C ends
// a solve within a step (InterruptibleSolve).
#include "contact_ode/analysis/contact_advisor.hpp"
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/law_registry.hpp"
#include "contact_ode/models/scene_registry.hpp"
#include "interruptible_solve.hpp"
#include "result_state.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>

namespace py = pybind11;
using namespace contact;

namespace {

py::list parameters(const std::vector<ParameterInfo>& list) {
  py::list out;
  for (const auto& p : list)
    out.append(py::dict(py::arg("name") = p.name, py::arg("unit") = p.unit,
                        py::arg("default") = p.default_value, py::arg("description") = p.description,
                        py::arg("accepted") = p.accepted.to_string()));
  return out;
}

template <class Row>
py::array_t<double> column(const std::vector<Row>& rows, const std::function<double(const Row&)>& get) {
  py::array_t<double> a(static_cast<py::ssize_t>(rows.size()));
  auto v = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < rows.size(); ++i) v(static_cast<py::ssize_t>(i)) = get(rows[i]);
  return a;
}

// A switch is True or False (Python's or NumPy's): pybind11 would take any object's truth, so that
// warm_start=None ran without warm starting and warm_start=float('nan') with it.
bool switch_value(const py::handle& v) {
  if (!py::isinstance<py::bool_>(v) && !py::isinstance(v, py::module_::import("numpy").attr("bool_")))
    throw py::cast_error("not a bool");
  return v.cast<bool>();
}

// The kinds of value a keyword takes, as a refusal names them.
enum class Kind { Number, Whole, Text, Switch };
const char* kind_text(Kind kind) {
  static constexpr const char* texts[] = {"a number", "a whole number", "a string", "True or False"};
  return texts[static_cast<int>(kind)];
}

// The method settings a keyword can set, each with the kind of value it takes and how it is read.
struct Setting {
  Kind kind;
  std::function<void(Method&, const py::handle&)> set;
};
const std::map<std::string, Setting>& method_settings() {
  static const std::map<std::string, Setting> settings = {
      // A fixed-step method's step; for penalty and event-driven runs, their integrator's.
      {"dt",
       {Kind::Number,
        [](Method& m, const py::handle& v) {
          (method_info(m.name).fixed_step ? m.dt : m.integrator.dt) = v.cast<double>();
        }}},
      {"rtol", {Kind::Number, [](Method& m, const py::handle& v) { m.integrator.rtol = v.cast<double>(); }}},
      {"atol", {Kind::Number, [](Method& m, const py::handle& v) { m.integrator.atol = v.cast<double>(); }}},
      {"integrator",
       {Kind::Text, [](Method& m, const py::handle& v) { m.integrator.method = v.cast<std::string>(); }}},
      {"max_steps",
       {Kind::Whole, [](Method& m, const py::handle& v) { m.integrator.max_steps = v.cast<long>(); }}},
      {"jacobian",
       {Kind::Text,
        [](Method& m, const py::handle& v) {
          m.integrator.jacobian = parse_jacobian(v.cast<std::string>());
        }}},
      // The implicit SUNDIALS integrators' linear solver: band, klu or gmres for a long chain.
      {"linear_solver",
       {Kind::Text,
        [](Method& m, const py::handle& v) {
          m.integrator.linear_solver = parse_linear_solver(v.cast<std::string>());
        }}},
      {"rest_speed", {Kind::Number, [](Method& m, const py::handle& v) { m.rest_speed = v.cast<double>(); }}},
      // The bounce height below which an event-driven contact rests (< 0: 100 atol for a numerical
      // flight, 0 for the exact one): the remedy an 'unresolved' run's message names.
      {"rest_height",
       {Kind::Number, [](Method& m, const py::handle& v) { m.rest_height = v.cast<double>(); }}},
      // The event-driven cap on impacts (ZenoLimit names it when a run reaches it).
      {"max_events", {Kind::Whole, [](Method& m, const py::handle& v) { m.max_events = v.cast<long>(); }}},
      {"iterations", {Kind::Whole, [](Method& m, const py::handle& v) { m.iterations = v.cast<int>(); }}},
      {"substeps", {Kind::Whole, [](Method& m, const py::handle& v) { m.substeps = v.cast<int>(); }}},
      {"warm_start", {Kind::Switch, [](Method& m, const py::handle& v) { m.warm_start = switch_value(v); }}},
      {"erp", {Kind::Number, [](Method& m, const py::handle& v) { m.erp = v.cast<double>(); }}},
      {"split_impulse",
       {Kind::Switch, [](Method& m, const py::handle& v) { m.split_impulse = switch_value(v); }}},
      {"restitution_threshold",
       {Kind::Number, [](Method& m, const py::handle& v) { m.restitution_threshold = v.cast<double>(); }}},
      {"contact_hertz",
       {Kind::Number, [](Method& m, const py::handle& v) { m.contact_hertz = v.cast<double>(); }}},
      {"contact_damping_ratio",
       {Kind::Number, [](Method& m, const py::handle& v) { m.contact_damping_ratio = v.cast<double>(); }}},
      {"push_max", {Kind::Number, [](Method& m, const py::handle& v) { m.push_max = v.cast<double>(); }}},
      {"theta", {Kind::Number, [](Method& m, const py::handle& v) { m.theta = v.cast<double>(); }}},
  };
  return settings;
}

// The tolerances and integrator up front, whether or not the method builds an integrator (solve()
// checks the other settings).
void check_integrator(const Method& m) {
  if (!(m.integrator.rtol > 0 && m.integrator.rtol < 1))
    throw std::invalid_argument(
        fmt::format("rtol: value '{}' is out of range; accepted range (0, 1)", m.integrator.rtol));
  if (!(m.integrator.atol > 0))
    throw std::invalid_argument(
        fmt::format("atol: value '{}' is out of range; accepted range (0, inf)", m.integrator.atol));
  integrator_info(m.integrator.method);  // throws naming the accepted integrators
}

// A setting the method does not read changes nothing: say so, as SciPy's solve_ivp does, rather
// than let a caller believe it took effect (a loop over methods may pass every setting to each).
// rtol is read by the method but not by an explicit integrator at a fixed step (reads_rtol).
// atol is read all the same: it sets a penalty run's switching offset and an event-driven run's
// rest height (100 atol), whatever the integrator.
void warn_of_ignored_settings(const Method& m, const py::kwargs& options) {
  const auto& reads = method_info(m.name).settings;
  const bool rtol_unread =
      std::find(reads.begin(), reads.end(), "rtol") != reads.end() && !reads_rtol(m.integrator);
  std::vector<std::string> ignored;
  bool rtol_given = false;
  for (const auto& [key, value] : options) {
    const auto name = key.cast<std::string>();
    if (method_settings().count(name) && std::find(reads.begin(), reads.end(), name) == reads.end())
      ignored.push_back(name);
    else if (name == "rtol")
      rtol_given = true;
  }
  std::string message;
  if (!ignored.empty())
    message = fmt::format("{} {} no effect on method '{}'; its settings: {}", fmt::join(ignored, ", "),
                          ignored.size() == 1 ? "has" : "have", m.name,
                          reads.empty() ? "none" : fmt::format("{}", fmt::join(reads, ", ")));
  if (rtol_unread && rtol_given)
    message += fmt::format("{}rtol has no effect on integrator '{}' {}", message.empty() ? "" : "; ",
                           m.integrator.method,
                           is_exact(integrator_info(m.integrator.method))
                               ? "(the exact solution: no tolerance)"
                               : "at a fixed step (no error control; its accuracy is set by dt)");
  if (!message.empty() && PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 2) != 0)
    throw py::error_already_set();
}

// A bool is a Python int, which pybind11 casts to 1.0 or 0: dt=True ran the game at a 1 s step.
// Only the on/off settings take one.
bool is_bool(const py::handle& value) {
  return py::isinstance<py::bool_>(value) ||
         py::isinstance(value, py::module_::import("numpy").attr("bool_"));
}

// A keyword whose value `kind` could not take, named like one out of range.
[[noreturn]] void refuse_value(const std::string& name, const py::handle& value, Kind kind) {
  // An int where a number is taken that does not fit the setting's C++ type (max_steps=2**63).
  const bool too_large = py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value) &&
                         (kind == Kind::Number || kind == Kind::Whole);
  throw std::invalid_argument(
      fmt::format("{}: value '{}' {}; accepted: {}", name, py::str(value).cast<std::string>(),
                  too_large ? "is out of range" : "has the wrong type", kind_text(kind)));
}

// Whether `name` is one of the scene's parameters (solve() also takes settings; methods_for not).
bool is_parameter_of(const SceneEntry& entry, const std::string& name) {
  return std::any_of(entry.parameters.begin(), entry.parameters.end(),
                     [&](const ParameterInfo& p) { return p.name == name; });
}

RunResult run(const std::string& scene, const std::string& method, const std::string& law,
              const py::kwargs& options, const py::object& error_type) {
  const SceneEntry& entry = scene_entry(scene);
  ParameterValues values;
  Method m{.name = method};
  SolveOptions span{.t_end = entry.t_end, .sample_dt = entry.t_end / 200};
  for (const auto& [key, value] : options) {
    const auto name = key.cast<std::string>();
    const bool is_parameter = is_parameter_of(entry, name);
    if (!is_parameter && !method_settings().count(name) && name != "t_end" && name != "sample_dt" &&
        name != "max_records") {
      std::string accepted = "t_end, sample_dt, max_records";
      for (const auto& p : entry.parameters) accepted += ", " + p.name;
      for (const auto& s : method_settings()) accepted += ", " + s.first;
      throw std::invalid_argument(
          fmt::format("{}: not an option of scene '{}' or of a method; accepted: {}", name, scene, accepted));
    }
    const Kind kind = is_parameter || name == "t_end" || name == "sample_dt" ? Kind::Number
                      : name == "max_records"                                ? Kind::Whole
                                              : method_settings().at(name).kind;
    try {  // a value of the wrong type is named like one out of range
      if (is_bool(value) && kind != Kind::Switch) throw py::cast_error();
      if (is_parameter)
        values[name] = value.cast<double>();
      else if (name == "t_end")
        span.t_end = value.cast<double>();
      else if (name == "sample_dt")
        span.sample_dt = value.cast<double>();
      else if (name == "max_records")
        span.limits.max_records = value.cast<long>();
      else
        method_settings().at(name).set(m, value);
    } catch (const py::cast_error&) {
      refuse_value(name, value, kind);
    }
  }
  check_integrator(m);
  warn_of_ignored_settings(m, options);
  const auto model = make_scene(scene, values, law);
  python::InterruptibleSolve interruptible;
  RunResult r;
  {
    // Other Python threads run meanwhile (a sweep over threads runs its solves side by side): the
    // library keeps no shared state but the stop request, and the engines whose libraries keep
    // process-wide state (ODE, Siconos) hold one world at a time themselves.
    const py::gil_scoped_release others_run;
    r = solve(*model, m, span);
  }
  interruptible.hand_over();
  if (!r.ok()) {
    py::object err = error_type(fmt::format("{} on {}: {} at t = {:.9g} s: {}", method, scene,
                                            to_string(r.status), r.t_reached, r.message));
    err.attr("status") = r.status;
    err.attr("t_reached") = r.t_reached;
    err.attr("solver_message") = r.message;
    err.attr("result") = py::cast(r);
    PyErr_SetObject(error_type.ptr(), err.ptr());
    throw py::error_already_set();
  }
  return r;
}

// The library names options as the command line does ("--t-end: value ...", "--max-penetration /
// --duration: give exactly one"); Python callers know them as keywords ("t_end: value ...").
// Every such name in the message, not only its first (the advisor's said "max_penetration /
// --duration").
std::string python_names(const std::string& message) {
  std::string out;
  for (std::size_t i = 0; i < message.size(); ++i) {
    const bool starts_name = message.compare(i, 2, "--") == 0 && i + 2 < message.size() &&
                             std::islower(static_cast<unsigned char>(message[i + 2])) &&
                             (i == 0 || !std::isalnum(static_cast<unsigned char>(message[i - 1])));
    if (!starts_name) {
      out += message[i];
      continue;
    }
    for (i += 2;
         i < message.size() && (std::isalnum(static_cast<unsigned char>(message[i])) || message[i] == '-');
         ++i)
      out += message[i] == '-' ? '_' : message[i];
    --i;
  }
  return out;
}

// A registry as a list of dicts, one per entry.
template <class Entries, class ToDict>
py::list listing(const Entries& entries, ToDict to_dict) {
  py::list out;
  for (const auto& entry : entries) out.append(to_dict(entry));
  return out;
}

py::dict spring_contact(const SpringContact& c) {
  return py::dict(py::arg("duration") = c.duration, py::arg("max_penetration") = c.max_penetration,
                  py::arg("exit_speed") = c.exit_speed);
}

// The advice under the names of contact_advisor's table (advice.csv's quantities).
py::dict advice_dict(const ContactRequest& q, const ContactAdvice& a) {
  return py::dict(
      py::arg("law") = describe(a.law), py::arg("k_lin") = a.k_lin, py::arg("c_lin") = a.c_lin,
      py::arg("omega") = a.omega, py::arg("frequency_hz") = a.frequency_hz, py::arg("zeta") = a.zeta,
      py::arg("euler_max_dt") = a.euler_max_dt, py::arg("symplectic_max_dt") = a.symplectic_max_dt,
      py::arg("game_dt") = a.game_dt, py::arg("ode_erp") = a.ode.erp, py::arg("ode_cfm") = a.ode.cfm,
      py::arg("mujoco_timeconst") = a.mujoco.timeconst, py::arg("mujoco_dampratio") = a.mujoco.dampratio,
      py::arg("mujoco_stiffness") = a.mujoco_direct.stiffness,
      py::arg("mujoco_damping") = a.mujoco_direct.damping, py::arg("box2d_hertz") = a.box2d.hertz,
      py::arg("box2d_damping_ratio") = a.box2d.damping_ratio,
      py::arg("drake_penetration_allowance") = a.drake.penetration_allowance,
      py::arg("drake_dissipation") = a.drake.dissipation,
      py::arg("requested_penetration") = q.max_penetration,
      py::arg("achieved_penetration") = a.achieved_penetration, py::arg("requested_duration") = q.duration,
      py::arg("achieved_duration") = a.achieved_duration, py::arg("requested_restitution") = q.e,
      py::arg("achieved_restitution") = a.achieved_restitution,
      py::arg("game_energy_error") = a.game_energy_error);
}

}  // namespace

PYBIND11_MODULE(contact_ode, mod) {
  mod.doc() = "contact-ode: contact resolution as ODEs (penalty, game, time-stepping, event-driven)";
  // NumPy now, not at the first solve's options (0.2 s of CPU): that solve's Ctrl-C window
  // (InterruptibleSolve) opened only after it, and a Ctrl-C meanwhile waited for the whole solve.
  py::module_::import("numpy");
  // Every refusal, from any function here, is a ValueError naming the keywords (python_names).
  py::register_local_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const std::invalid_argument& refused) {
      PyErr_SetString(PyExc_ValueError, python_names(refused.what()).c_str());
    }
  });

  py::enum_<Status>(mod, "Status")
      .value("success", Status::Success)
      .value("max_steps", Status::MaxSteps)
      .value("convergence_failure", Status::ConvergenceFailure)
      .value("error_test_failure", Status::ErrorTestFailure)
      .value("non_finite_state", Status::NonFiniteState)
      .value("diverged", Status::Diverged)
      .value("zeno_limit", Status::ZenoLimit)
      .value("unresolved", Status::Unresolved)
      .value("no_progress", Status::NoProgress)
      .value("work_limit", Status::WorkLimit)
      .value("interrupted", Status::Interrupted)
      .value("solver_error", Status::SolverError);
  static py::exception<SolverFailure> solver_error(mod, "SolverError", PyExc_RuntimeError);
  solver_error.doc() = "a run that failed: .status, .t_reached, .solver_message and the partial .result";

  py::class_<RunResult>(
      mod, "Result",
      "A run: t, y (a row per sample, columns state_labels), energy and dissipated (the "
      "ledger: energy + dissipated stays energy0 to the method's accuracy) as NumPy "
      "arrays; contacts (contact, t_begin, t_end, max_penetration, v_in, v_out, in the order they "
      "began), apexes (contact, t, gap, energy, dissipated: the tops of a contact's bounces, none "
      "before its first impact) and notifications (the batched begin / end "
      "events of the game loops: contact, begin, step, t) as dicts of arrays; stats (steps, "
      "right-hand sides, Jacobians, Newton and linear iterations, ..., the run's wall time and "
      "the CPU time of an engine's world construction before it); status, t_reached "
      "and message.")
      .def_readonly("method", &RunResult::method)
      .def_readonly("state_labels", &RunResult::state_labels)
      .def_readonly("status", &RunResult::status)
      .def_readonly("t_reached", &RunResult::t_reached)
      .def_readonly("message", &RunResult::message)
      .def_readonly("energy0", &RunResult::energy0)
      .def(py::pickle(&python::result_state, &python::result_from_state))
      .def_property_readonly(
          "t",
          [](const RunResult& r) { return column<Sample>(r.samples, [](const Sample& s) { return s.t; }); })
      .def_property_readonly("energy",
                             [](const RunResult& r) {
                               return column<Sample>(r.samples, [](const Sample& s) { return s.energy; });
                             })
      .def_property_readonly("dissipated",
                             [](const RunResult& r) {
                               return column<Sample>(r.samples, [](const Sample& s) { return s.dissipated; });
                             })
      .def_property_readonly("y",
                             [](const RunResult& r) {
                               const auto n = static_cast<py::ssize_t>(r.samples.size());
                               const auto d = static_cast<py::ssize_t>(r.state_labels.size());
                               py::array_t<double> a({n, d});
                               auto v = a.mutable_unchecked<2>();
                               for (py::ssize_t i = 0; i < n; ++i)
                                 for (py::ssize_t j = 0; j < d; ++j)
                                   v(i, j) = r.samples[static_cast<std::size_t>(i)].y[j];
                               return a;
                             })
      .def_property_readonly(
          "contacts",
          [](const RunResult& r) {
            using C = ContactRecord;
            return py::dict(py::arg("contact") = column<C>(
                                r.contacts, [](const C& c) { return static_cast<double>(c.contact); }),
                            py::arg("t_begin") = column<C>(r.contacts, [](const C& c) { return c.t_begin; }),
                            py::arg("t_end") = column<C>(r.contacts, [](const C& c) { return c.t_end; }),
                            py::arg("max_penetration") =
                                column<C>(r.contacts, [](const C& c) { return c.max_penetration; }),
                            py::arg("v_in") = column<C>(r.contacts, [](const C& c) { return c.v_in; }),
                            py::arg("v_out") = column<C>(r.contacts, [](const C& c) { return c.v_out; }));
          })
      .def_property_readonly(
          "apexes",
          [](const RunResult& r) {
            return py::dict(
                py::arg("contact") =
                    column<Apex>(r.apexes, [](const Apex& a) { return static_cast<double>(a.contact); }),
                py::arg("t") = column<Apex>(r.apexes, [](const Apex& a) { return a.t; }),
                py::arg("gap") = column<Apex>(r.apexes, [](const Apex& a) { return a.gap; }),
                py::arg("energy") = column<Apex>(r.apexes, [](const Apex& a) { return a.energy; }),
                py::arg("dissipated") = column<Apex>(r.apexes, [](const Apex& a) { return a.dissipated; }));
          })
      .def_property_readonly(
          "notifications",
          [](const RunResult& r) {
            using N = CollisionEvent;
            return py::dict(
                py::arg("contact") =
                    column<N>(r.notifications, [](const N& n) { return static_cast<double>(n.contact); }),
                py::arg("begin") = column<N>(r.notifications,
                                             [](const N& n) { return n.kind == N::Kind::Begin ? 1.0 : 0.0; })
                                       .attr("astype")(py::module_::import("numpy").attr("bool_")),
                py::arg("step") =
                    column<N>(r.notifications, [](const N& n) { return static_cast<double>(n.step); }),
                py::arg("t") = column<N>(r.notifications, [](const N& n) { return n.t; }));
          })
      .def_property_readonly("stats", [](const RunResult& r) {
        const SolverStats& s = r.stats;
        return py::dict(py::arg("steps") = s.steps, py::arg("failed_steps") = s.failed_steps,
                        py::arg("rhs_evals") = s.rhs_evals, py::arg("jac_evals") = s.jac_evals,
                        py::arg("newton_iters") = s.newton_iters, py::arg("linear_setups") = s.linear_setups,
                        py::arg("linear_iters") = s.linear_iters, py::arg("root_evals") = s.root_evals,
                        py::arg("events") = s.events, py::arg("restarts") = s.restarts,
                        py::arg("wall_time_s") = s.wall_time_s, py::arg("setup_cpu_s") = s.setup_cpu_s);
      });

  static const std::string solve_doc = fmt::format(
      "Runs `method` on `scene` (with contact law `law` where the scene takes one; '': the scene's "
      "default_law in scenes(): hooke, undamped, which a penalty run takes without e; name "
      "'kelvin-voigt' for a spring damped to e). Keywords: the scene's parameters, the method's "
      "settings (methods() lists each one's), t_end, sample_dt and max_records (the contact records "
      "and apexes a run may keep, {} by default).",
      RunLimits{}.max_records);
  mod.def(
      "solve",
      [](const std::string& scene, const std::string& method, const std::string& law,
         const py::kwargs& options) { return run(scene, method, law, options, solver_error); },
      py::arg("scene"), py::arg("method"), py::arg("law") = "", solve_doc.c_str());

  mod.def(
      "scenes",
      [] {
        return listing(scene_registry(), [](const auto& s) {
          return py::dict(py::arg("name") = s.name, py::arg("description") = s.description,
                          py::arg("parameters") = parameters(s.parameters),
                          py::arg("takes_law") = !s.default_law.empty(),
                          py::arg("default_law") = s.default_law, py::arg("observables") = s.observables,
                          py::arg("exact") = s.exact, py::arg("t_end") = s.t_end);
        });
      },
      "The scenes solve() runs, one dict each: name, description, parameters (name, unit, default,\n"
      "description, accepted range), takes_law, default_law, observables, exact (its closed forms) and\n"
      "t_end (the default end time [s]).");
  mod.def(
      "laws",
      [] {
        return listing(law_registry(), [](const auto& l) {
          return py::dict(py::arg("name") = l.name, py::arg("description") = l.description,
                          py::arg("exponent") = l.exponent, py::arg("damped") = l.damped,
                          py::arg("closed_forms") = l.closed_forms,
                          py::arg("parameters") = parameters(l.parameters));
        });
      },
      "The contact laws, one dict each: name, description, exponent (n of K delta^n), damped,\n"
      "closed_forms (what co.references has for it) and parameters, as in scenes().");
  mod.def(
      "methods",
      [] {
        return listing(method_registry(), [](const auto& m) {
          return py::dict(py::arg("name") = m.name, py::arg("description") = m.description,
                          py::arg("family") = m.family, py::arg("fixed_step") = m.fixed_step,
                          py::arg("uses_contact_law") = m.uses_contact_law, py::arg("needs") = m.needs,
                          py::arg("settings") = m.settings);
        });
      },
      "The methods solve() runs, one dict each: name, description, family (penalty, game, event-driven,\n"
      "time-stepping, engine), fixed_step, uses_contact_law, needs (what a scene must provide) and\n"
      "settings (the keywords solve() reads for it).");
  mod.def(
      "integrators",
      [] {
        return listing(integrator_catalog(), [](const auto& i) {
          return py::dict(py::arg("name") = i.name, py::arg("family") = i.family, py::arg("order") = i.order,
                          py::arg("adaptive") = i.adaptive, py::arg("implicit") = i.implicit,
                          py::arg("description") = i.description);
        });
      },
      "The ODE integrators a penalty or event-ode run takes as integrator=, one dict each: name, family,\n"
      "order, adaptive (error-controlled), implicit and description.");
  // Which methods run a scene can depend on its parameters (a Hunt-Crossley law is linear only at
  // e = 1, and only a linear law runs under xpbd, mujoco-spring or ode-spring): the scene is made
  // with the parameters solve() would be given, not only at its defaults.
  mod.def(
      "methods_for",
      [](const std::string& scene, const std::string& law, const py::kwargs& parameters) {
        const SceneEntry& entry = scene_entry(scene);
        ParameterValues values;
        for (const auto& [key, value] : parameters) {
          const auto name = key.cast<std::string>();
          if (!is_parameter_of(entry, name)) {
            std::vector<std::string> accepted;
            for (const auto& p : entry.parameters) accepted.push_back(p.name);
            throw std::invalid_argument(fmt::format("{}: not a parameter of scene '{}'; accepted: {}", name,
                                                    scene, fmt::join(accepted, ", ")));
          }
          try {
            if (is_bool(value)) throw py::cast_error();
            values[name] = value.cast<double>();
          } catch (const py::cast_error&) {
            refuse_value(name, value, Kind::Number);
          }
        }
        return methods_for(*make_scene(scene, values, law));
      },
      py::arg("scene"), py::arg("law") = "",
      "The names of the methods that can run `scene` (with contact law `law`; '': its default_law) with\n"
      "the scene parameters given as keywords (the rest at their defaults), in methods() order: what\n"
      "solve(scene, method, law, **parameters) accepts.");

  // Each closed form says what it computes, in which units, and where it holds: help() showed the
  // signatures alone, and a 0-based loop over the impacts read the first one twice.
  auto refs = mod.def_submodule(
      "references",
      "Closed forms of the ball drop and of a single spring contact (analysis/references.hpp), in SI\n"
      "units. Each raises ValueError for arguments outside the domain its formula holds on.");
  refs.def(
      "hooke_contact",
      [](double m, double k, double V, double g) { return spring_contact(hooke_contact(m, k, V, g)); },
      py::arg("m"), py::arg("k"), py::arg("V"), py::arg("g") = 0.0,
      "One contact of a Hooke spring F = k delta (mass m [kg], stiffness k [N/m]) entered at speed\n"
      "V [m/s] under gravity g >= 0 [m/s^2] (V > 0, or 0 under gravity: a mass set down on the\n"
      "spring), exactly: a dict of duration [s], max_penetration [m] and exit_speed [m/s] (V).\n"
      "With w = sqrt(k/m): duration (pi + 2 atan(g / (w V))) / w and max_penetration\n"
      "g / w^2 + sqrt(g^2 / w^4 + V^2 / w^2); without gravity pi sqrt(m/k) and\n"
      "V sqrt(m/k).");
  refs.def(
      "kelvin_voigt_contact",
      [](double m, double k, double zeta, double V, double g) {
        return spring_contact(kelvin_voigt_contact(m, k, zeta, V, g));
      },
      py::arg("m"), py::arg("k"), py::arg("zeta"), py::arg("V"), py::arg("g") = 0.0,
      "One contact of a spring and dashpot F = k delta + c delta' of damping ratio\n"
      "zeta = c / (2 sqrt(k m)) in [0, 1], entered at speed V > 0 under gravity g >= 0, exactly: a\n"
      "dict of duration [s] (until the overlap closes), max_penetration [m] and exit_speed [m/s].\n"
      "Without gravity the duration is pi / w_d, w_d = sqrt(k/m) sqrt(1 - zeta^2), and the restitution\n"
      "exp(-zeta pi / sqrt(1 - zeta^2)); where the spring holds the mass for good (zeta = 1 without\n"
      "gravity, soft springs under it) the duration is inf and the exit speed 0.");
  refs.def(
      "clamped_kelvin_voigt_contact",
      [](double m, double k, double zeta, double V, double g) {
        return spring_contact(clamped_kelvin_voigt_contact(m, k, zeta, V, g));
      },
      py::arg("m"), py::arg("k"), py::arg("zeta"), py::arg("V"), py::arg("g") = 0.0,
      "As kelvin_voigt_contact, with the force clamped to F >= 0: the mass lets go while it still\n"
      "overlaps and flies freely until the overlap closes, where duration and exit_speed are taken.\n"
      "Without gravity the exit speed is V exp(-zeta (pi - 2 asin zeta) / sqrt(1 - zeta^2)), above\n"
      "the unclamped one. Duration and exit speed are nan where gravity's share g / (w V) is large\n"
      "enough that the clamp takes hold again before the overlap closes.");
  refs.def(
      "linear_law_first_contact",
      [](const std::string& law, double m, double k, double e, double V, double g) {
        law_info(law);  // an unknown law is a ValueError, not NaN
        const SpringContact c = linear_law_first_contact(law, m, k, e, V, g);
        if (std::isnan(c.max_penetration))  // a known law without a closed form here: not a silent NaN
          throw py::value_error(fmt::format(
              "linear_law_first_contact: law '{}' has no closed form here; accepted: hooke, kelvin-voigt, "
              "kelvin-voigt-clamped (a Hunt-Crossley law's restitution: hunt_crossley_restitution)",
              law));
        return spring_contact(c);
      },
      py::arg("law"), py::arg("m"), py::arg("k"), py::arg("e"), py::arg("V"), py::arg("g") = 0.0,
      "The first contact of a linear law of laws() as solve() builds it, tuned to restitution e:\n"
      "'hooke' (hooke_contact, e unused), 'kelvin-voigt' (kelvin_voigt_contact) or\n"
      "'kelvin-voigt-clamped' (clamped_kelvin_voigt_contact), with zeta =\n"
      "damping_ratio_for_restitution(e). A dict of duration [s], max_penetration [m], exit_speed [m/s].");
  refs.def("hunt_crossley_restitution", &hunt_crossley_restitution, py::arg("chi_v"),
           "The restitution of a Hunt-Crossley contact F = K delta^n (1 + chi delta'), exact, without\n"
           "gravity: the root e of a - ln(1 + a) = -a e - ln(1 - a e), a = chi_v = chi V >= 0 (damping\n"
           "coefficient [s/m] times impact speed [m/s]). It depends on chi V alone, whatever n, K and m;\n"
           "1 - e^2 = (4/3) chi V to first order.");
  refs.def("damping_ratio_for_restitution", &damping_ratio_for_restitution, py::arg("e"),
           "The damping ratio zeta = |ln e| / sqrt(pi^2 + ln^2 e) of a linear spring and dashpot whose\n"
           "contact, without gravity, has restitution e in [0, 1] (0 for e = 1; 1, critical, for e = 0).");
  static const char* const kCountedFromOne =
      "h0 >= 0 [m] the release height, v0 [m/s] the release velocity (up positive), g > 0 [m/s^2],\n"
      "e in [0, 1] Newton's restitution; n = 1, 2, ...: impacts and apexes are counted from 1 (apex n\n"
      "follows impact n, and is element n - 1 of a solve()'s apexes), n = 0 a ValueError.";
  static const std::string apex_doc =
      std::string(
          "The height [m] of the apex after the n-th impact of a rigid ball, (e^n V)^2 / (2 g) with\n"
          "V = sqrt(v0^2 + 2 g h0) (e^(2n) h0 when v0 = 0).\n") +
      kCountedFromOne;
  static const std::string impact_doc =
      std::string(
          "The time [s] of the n-th impact of a rigid ball: T1 = (v0 + V) / g, then\n"
          "T(n+1) = T(n) + 2 e^n V / g, V = sqrt(v0^2 + 2 g h0).\n") +
      kCountedFromOne;
  refs.def(
      "rigid_apex_height",
      [](double h0, double v0, double g, double e, std::size_t n) {
        return RigidBounces(h0, v0, g, e).apex_height(n);
      },
      py::arg("h0"), py::arg("v0"), py::arg("g"), py::arg("e"), py::arg("n"), apex_doc.c_str());
  refs.def(
      "rigid_impact_time",
      [](double h0, double v0, double g, double e, std::size_t n) {
        return RigidBounces(h0, v0, g, e).impact_time(n);
      },
      py::arg("h0"), py::arg("v0"), py::arg("g"), py::arg("e"), py::arg("n"), impact_doc.c_str());
  refs.def(
      "zeno_time",
      [](double h0, double v0, double g, double e) { return RigidBounces(h0, v0, g, e).zeno_time(); },
      py::arg("h0"), py::arg("v0"), py::arg("g"), py::arg("e"),
      "The time [s] at which a rigid ball's impacts accumulate, T1 + 2 e V / (g (1 - e)) (inf for\n"
      "e = 1), with T1 and V as in rigid_impact_time: t0 (1 + e) / (1 - e) for v0 = 0, t0 = sqrt(2 h0 / g).");

  mod.def(
      "advise",
      [](double m, double v, double e, std::optional<double> max_penetration, std::optional<double> duration,
         const std::string& law, std::optional<std::string> rule, std::optional<double> radius,
         std::optional<double> young, std::optional<double> poisson, double energy_error, double engine_step,
         double g) {
        ContactRequest q{.m = m,
                         .v = v,
                         .e = e,
                         .max_penetration = max_penetration,
                         .duration = duration,
                         .law = law,
                         .radius = radius,
                         .young = young,
                         .poisson = poisson,
                         .energy_error = energy_error,
                         .engine_step = engine_step,
                         .g = g};
        if (rule) q.rule = parse_damping_rule(*rule);
        validate(q);
        return advice_dict(q, advise(q));
      },
      py::arg("m"), py::arg("v"), py::arg("e"), py::arg("max_penetration") = py::none(),
      py::arg("duration") = py::none(), py::arg("law") = "kelvin-voigt", py::arg("rule") = py::none(),
      py::arg("radius") = py::none(), py::arg("young") = py::none(), py::arg("poisson") = py::none(),
      py::arg("energy_error") = ContactRequest{}.energy_error,
      py::arg("engine_step") = ContactRequest{}.engine_step, py::arg("g") = ContactRequest{}.g,
      "The stiffness advisor, as the contact_advisor program: a law, its linearisation, stable steps and\n"
      "the engines' parameters for a requirement (exactly one of max_penetration and duration, or for\n"
      "hertz a material: radius, young and poisson), each checked by simulation. rule: the damping rule\n"
      "of the Hunt-Crossley laws (hertz, hunt-crossley-linear), exact (meets e) by default; energy_error:\n"
      "the energy error per contact game_dt may cost; engine_step: the step of ODE's and Bullet's ERP\n"
      "and CFM; g: gravity for Drake's penetration allowance.");
}
