#include "contact_ode/integrators/penalty.hpp"

#include "contact_ode/integrators/method_registry.hpp"

#include "contact_ode/integrators/capabilities.hpp"
#include "integrator_driver.hpp"
#include "normal_kept.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace contact {

namespace {

// Whether each contact's switch on was located finely enough for the contact it starts. A switch is
// taken at contact_threshold of overlap and located in time to the root finding's resolution (about
// 100 u |t| under SUNDIALS); the spring then starts from the energy it stores there, which an exact
// switch would not give it. For an undamped spring that energy is what the bounce gains (measured:
// a 1 kg ball at k = 1e24 N/m, rtol 1e-10, gained 4.64e-5 of its energy against 4.64e-5 stored at
// the switch; at 1e29 it left with 6 times its energy, a 'success'). Against the spring's energy
// at the contact's deepest it is the switch's share of the contact's error: above 1000 rtol (BDF's
// own energy error per contact measures 10 to 100 rtol at rtol 1e-6 and 1e-8, about 1000 at 1e-10,
// so the switch's would match or pass it) or half the contact's energy whatever the tolerance, the
// contact is not resolved and the run fails, Status::Unresolved. A method without error control
// (exact-linear, the fixed steps) is held to the default rtol's bound: exact-linear, exact to
// rounding between switches, let the ball at k = 1e29 leave with 28 times its energy. Only for
// contacts that begin at a located switch (not those engaged at the start, whose overlap is the
// scene's), and only where the switch's energy shows in the run's, above rtol |E0|: a graze a few
// thresholds deep beside a scene's real impacts stores next to nothing, and its run's numbers stand.
// Each contact's end is held to the same bound (require_parting).
class SwitchResolution {
 public:
  SwitchResolution(std::size_t contacts, const PenaltyOptions& opt, double energy0)
      : checked_(opt.locate_switches),
        bound_(std::min(1000 * controlled_rtol(opt.integrator), 0.5)),
        visible_(controlled_rtol(opt.integrator) * std::abs(energy0)),
        threshold_(contact_threshold(opt.integrator)),
        options_(opt.integrator),
        on_(contacts, kNone),
        overlap_(contacts, 0.0),
        peak_(contacts, 0.0) {}

  // A contact ends where its overlap closes: the gap rises through zero, so its rate there is not
  // negative. A rate still approaching is a step that crossed the contact without resolving it: an
  // explicit step beyond its stability for the law's stiffness and damping gives a position and a
  // velocity that disagree. Measured: two balls meeting at 1 m/s, e = 0, arkode-erk at dt = 3e-3 s:
  // 35843 'contacts' each ending still approaching, 'success'; a sphere of 3 g into a cuboid at
  // 1e-3 s: 442382 of them and the sphere leaving sideways at 0.085 m/s that it never had. Allowed:
  // the bound's share of the contact's entry speed or of the state's fastest velocity (the rate's
  // error comes from theirs: after a contact at e = 0 two balls move on together at 0.5 m/s, and
  // graze at 5e-10 m/s under rtol 1e-6), and atol.
  void require_parting(std::size_t i, double t, double v_in, double v_out, double speed) const {
    if (!(v_out < -(bound_ * std::max(std::abs(v_in), speed) + options_.atol))) return;
    std::string remedy =
        fmt::format("integrator '{}' has no error control: choose an adaptive one", options_.method);
    if (options_.dt > 0)
      remedy = fmt::format(
          "a fixed step of dt = {:g} s is too long for the contact's stiffness and damping: "
          "lower dt, or leave it at 0 for error control",
          options_.dt);
    else if (integrator_info(options_.method).adaptive)
      remedy = fmt::format("tighten rtol (now {:g})", options_.rtol);
    throw SolverFailure(
        Status::Unresolved, t,
        fmt::format("contact {} ended with its bodies still approaching at {:.3g} m/s (it began "
                    "at {:.3g} m/s): the step crossed the contact without resolving it; {}",
                    i, -v_out, -v_in, remedy));
  }

  void begin(std::size_t i, double energy, double overlap) {
    on_[i] = energy;
    overlap_[i] = overlap;
    peak_[i] = energy;
  }
  void observe(std::size_t i, double energy) { peak_[i] = std::max(peak_[i], energy); }

  // At the contact's deepest, or its switch off if that comes first: throws SolverFailure when the
  // switch on stored more than the bound allows.
  void check(std::size_t i, double t) {
    const double on = std::exchange(on_[i], kNone);
    if (!checked_ || std::isnan(on) || !(on > bound_ * peak_[i]) || !(on > visible_)) return;
    throw SolverFailure(
        Status::Unresolved, t,
        fmt::format("contact {} was switched on {:.3g} m into its overlap, its spring storing {:.3g} J there "
                    "against {:.3g} J at the contact's deepest ({:.2g} of it, above {:.2g}: 1000 rtol, the "
                    "default's for a method without error control, at most 1/2): the contact is too short "
                    "or too shallow for the run to resolve. A switch is taken at 1e-3 atol = {:.3g} m of "
                    "overlap (a tighter atol lowers it) and located in time to about 100 u |t| = {:.3g} s "
                    "(no tolerance shortens that; a softer contact lasts longer)",
                    i, overlap_[i], on, peak_[i], on / peak_[i], bound_, threshold_,
                    100 * std::numeric_limits<double>::epsilon() * std::abs(t)));
  }

 private:
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  static double controlled_rtol(const IntegratorOptions& o) {
    const bool adaptive = o.dt == 0 && integrator_info(o.method).adaptive;
    return adaptive ? o.rtol : IntegratorOptions{}.rtol;
  }
  bool checked_;
  double bound_, visible_, threshold_;
  IntegratorOptions options_;
  std::vector<double> on_, overlap_, peak_;
};

}  // namespace

RunResult run_penalty(const Dynamics& model, const PenaltyOptions& opt, const SolveOptions& span) {
  const std::size_t nc = model.contact_count();
  const ContactGeometry& geo = contact_geometry(model);
  RunRecorder rec(model, "penalty " + opt.integrator.method, span);
  const Vector y0 = model.initial_state();
  // The held modes: the state's at the start, switched at the switching roots. The contact log
  // follows them and each switching root is offset towards them. With located switches the force
  // takes them too; without, the force's modes follow the state inside every call (state_modes),
  // while the roots keep to the held ones, so that a root function is a function of (t, y) alone
  // and not of whichever right-hand side ran last (what the root location takes it for).
  ContactModes held(nc);
  geo.modes_from_state(nc, y0, held);
  ContactModes state_modes = held;
  auto modes_at = [&](ConstVectorRef y) -> const ContactModes& {
    if (opt.locate_switches) return held;
    geo.modes_from_state(nc, y, state_modes);
    return state_modes;
  };
  OdeSystem base = mechanical_ode(model, modes_at);
  const double threshold = contact_threshold(opt.integrator);
  // Per contact: the switching function (offset towards the held mode), the gap rate (apexes and
  // maximum penetration) and, where a clamped law can let go while the bodies overlap, the gap
  // (the overlap closing after the release). Where no law can, the switch is the closing, and a
  // gap root would only stop the integrator once more per contact (a third of the root work of a
  // long chain). The rate's roots in both directions also catch bodies that meet and part within
  // one step: the search that brackets the rate's turn at their closest approach meets the overlap
  // and locates the switch first (event_driven.cpp).
  bool releasing = false;
  for (std::size_t i = 0; i < nc; ++i) releasing = releasing || geo.releases_while_overlapping(i);
  const std::size_t per = releasing ? 3 : 2;
  base.root_count = per * nc;
  std::vector<double> switching(nc), rates(nc);
  base.roots = [&](double, ConstVectorRef y, VectorRef g) {
    geo.switching_and_rates(y, switching, rates);
    for (std::size_t i = 0; i < nc; ++i) {
      const auto at = static_cast<Eigen::Index>(per * i);
      // Touching counts as the mode held (see contact_threshold).
      const double side = held[i] == ContactMode::Penalty ? threshold : -threshold;
      g[at] = switching[i] + side;
      g[at + 1] = rates[i];
      if (releasing) g[at + 2] = geo.gap(i, y) + threshold;
    }
  };
  // The energy ledger: the laws' dissipated power integrated as one more state, per kilogram of
  // the bodies' mean mass. In joules its error test hung on the unit of mass: against an atol made
  // for metres, a 1e-6 kg ball's ledger (1e-5 J) fell out of the test and a 1 kg ball's held the
  // steps of every contact, so the drop of 1e-6 kg took 686 steps for 766 and its first apex came
  // out 4.5e-7 m off the same motion at 1 kg (rtol 1e-8).
  const double ledger_unit = model.mean_mass();  // [J] per unit of the ledger state
  OdeSystem sys = with_ledger(std::move(base), [&](ConstVectorRef y) {
    double p = 0;
    const ContactModes& m = modes_at(y);
    for (std::size_t i = 0; i < nc; ++i)
      if (m[i] == ContactMode::Penalty) p += geo.dissipated_power(i, y);
    return p / ledger_unit;
  });
  const auto n = static_cast<Eigen::Index>(model.state_size());
  Vector y0_ledger(n + 1);
  y0_ledger << y0, 0.0;

  for (std::size_t i = 0; i < nc; ++i)
    if (held[i] == ContactMode::Penalty) rec.contact_begin(i, 0.0, geo.gap_rate(i, y0));

  // A contact lasts from the law's first push to the overlap's closing: a clamped law lets go
  // while the bodies still overlap, and gravity may still slow them until they separate, so
  // the record ends, and its outgoing speed is read, where the overlap closes. Its restitution
  // then agrees with the next apex and the energy after the bounce. At every switch the elastic
  // energy of the spring is booked beside the ledger (released: a physical loss; re-engaged at
  // an overlap: energy the law takes back), since energy() counts only engaged springs.
  double booked = 0.0;  // spring energy booked at switches [J], beside the ledger state
  SwitchResolution resolution(nc, opt, model.energy(y0));
  const Mask velocities = !model.position_mask();
  const auto end_contact = [&](std::size_t i, double t, ConstVectorRef y) {
    const double rate = geo.gap_rate(i, y);
    resolution.require_parting(i, t, rec.open_v_in(i), rate,
                               velocities.select(y.array().abs(), 0.0).maxCoeff());
    rec.contact_end(i, t, rate);
  };
  EventHandling drive;
  drive.on_roots = [&](double t, Vector& y_full, const std::vector<int>& roots) {
    const auto y = y_full.head(n);
    bool switched = false;
    for (std::size_t i = 0; i < nc; ++i) {
      const int sw = roots[per * i], rate = roots[per * i + 1], closing = releasing ? roots[per * i + 2] : 0;
      const bool engaged = modes_at(y)[i] == ContactMode::Penalty;
      if (rate > 0 && engaged) {
        // A spring too soft for its bodies (radius 1e-6 m at k = 1e6 N/m: 'success', the cue
        // leaving at 1.995 m/s of its 2): the gap rate jumps from approach to parting where the
        // centres cross, a root of the rate located there, at the extent to the root's resolution;
        // a smooth deepest point within 1e-3 of it is a contact whose normal is about to turn.
        require_normal_kept(geo, i, t, y, 0.0, 0.0);
        rec.observe_penetration(i, -geo.gap(i, y));
        resolution.observe(i, geo.elastic_energy(i, y));
        resolution.check(i, t);
      }
      if (rate < 0 && !engaged)
        rec.apex(i, t, geo.gap(i, y), model.energy(y), ledger_unit * y_full[n] + booked);
      if (sw > 0) {
        if (!rec.contact_open(i)) {
          rec.contact_begin(i, t, geo.gap_rate(i, y));
          resolution.begin(i, geo.elastic_energy(i, y), -geo.gap(i, y));
        }
        booked -= geo.elastic_energy(i, y);
      }
      if (sw < 0) {
        rec.observe_penetration(i, -geo.gap(i, y));
        resolution.observe(i, geo.elastic_energy(i, y));
        resolution.check(i, t);
        booked += geo.elastic_energy(i, y);
        if (geo.gap(i, y) >= 0) end_contact(i, t, y);
      }
      if (closing > 0 && sw == 0 && !engaged) end_contact(i, t, y);
      if (sw != 0) {
        held[i] = sw > 0 ? ContactMode::Penalty : ContactMode::Free;
        switched = switched || opt.locate_switches;  // a restart where the force's modes changed
      }
    }
    return switched;
  };
  drive.sample = [&](double t, ConstVectorRef y_full) {
    const auto y = y_full.head(n);
    for (std::size_t i = 0; i < nc; ++i) rec.observe_penetration(i, -geo.gap(i, y));
    rec.sample(t, y, ledger_unit * y_full[n] + booked);
  };
  return contact::drive(std::move(sys), y0_ledger, opt.integrator, rec, drive);
}

}  // namespace contact

namespace contact {

std::vector<MethodInfo> penalty_methods() {
  // penalty-dq's Jacobian is its own: a jacobian setting would change nothing there.
  auto settings = [](const std::optional<JacobianMode>& jacobian) {
    std::vector<std::string> s = kIntegratorSettings;
    if (jacobian) std::erase(s, "jacobian");
    return s;
  };
  // penalty takes the Jacobian the options ask for (analytic by default); penalty-dq always forms
  // difference quotients, the same run beside it with the solver's own Jacobian.
  auto entry = [settings](std::string name, std::string description, std::optional<JacobianMode> jacobian) {
    return MethodInfo{.name = std::move(name),
                      .description = std::move(description),
                      .family = "penalty",
                      .fixed_step = false,
                      .uses_contact_law = true,
                      .needs = "dynamics (and contact geometry for its springs)",
                      .can_run = [](const Dynamics&) { return true; },
                      .run =
                          [jacobian](const Dynamics& scene, const Method& m, const SolveOptions& span) {
                            PenaltyOptions o{.integrator = m.integrator};
                            if (jacobian) o.integrator.jacobian = *jacobian;
                            return run_penalty(scene, o, span);
                          },
                      .settings = settings(jacobian),
                      .dq_jacobian = jacobian == JacobianMode::DifferenceQuotient,
                      .working_doubles = kIntegratorWorkingDoubles};
  };
  return {entry("penalty",
                "penalty spring as an ODE (CVODE BDF by default), analytic Jacobian by default, switches "
                "root-located",
                std::nullopt),
          entry("penalty-dq", "as penalty, with the integrator's difference-quotient Jacobian",
                JacobianMode::DifferenceQuotient)};
}

}  // namespace contact
