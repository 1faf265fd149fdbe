#include "contact_ode/integrators/event_driven.hpp"

#include "contact_ode/integrators/method_registry.hpp"

#include "contact_ode/integrators/run_recorder.hpp"
#include "integrator_driver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace contact {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Contact i found overlapping by -gap at t with no impact located (at a sample or a closest approach).
SolverFailure unlocated_overlap(std::size_t i, double t, double gap) {
  return SolverFailure(
      Status::Unresolved, t,
      fmt::format("contact {} overlaps by {:.3g} m with no impact located: its bodies go on pressing "
                  "together after an impact (a sustained contact between free bodies, which impulses "
                  "do not model; a penalty or time-stepping method does)",
                  i, -gap));
}

// What happens at an impact, whichever flight located it.
class Impacts {
 public:
  // `numerical`: the flight is an integrator, with the resolution of its absolute tolerance.
  Impacts(const MechanicalSystem& model, const EventOptions& opt, RunRecorder& rec, bool numerical)
      : model_(model),
        opt_(opt),
        rec_(rec),
        numerical_(numerical),
        rest_height_(opt.rest_height >= 0 ? opt.rest_height
                     : numerical          ? 100 * opt.integrator.atol
                                          : 0.0),
        velocities_(!model.position_mask()),
        modes_(model.all_modes(ContactMode::Free)),
        last_(model.contact_count(), -kInf),
        ydot_(model.state_size()),
        y_ahead_(model.state_size()) {}

  const ContactModes& modes() const { return modes_; }
  bool resting(std::size_t i) const { return modes_[i] == ContactMode::Resting; }
  // A resting contact whose bodies part (driven apart by an impulse, or the gap opened past the
  // flight's resolution) flies free again, from the surface: left sunk by the flight's error, a
  // later approach would find its gap already closed and locate no impact.
  void leave_rest(std::size_t i, VectorRef y) {
    modes_[i] = ContactMode::Free;
    const double before = rec_.energy(y);
    model_.project(i, y);
    rec_.add_dissipated(before - rec_.energy(y));
  }
  // A resting contact that the flight's error let sink into its support (a ball sliding over a
  // dome: the support holds the gap's second derivative, not the gap) is put back on the surface,
  // an approach removed and the change booked. Not a leaving rate: near where the support lets go
  // the bodies part slowly, and removing it held the ball on the dome past that point.
  void resettle(std::size_t i, VectorRef y) {
    const double before = rec_.energy(y);
    if (model_.gap_rate(i, y) < 0)
      model_.settle(i, y);
    else
      model_.project(i, y);
    rec_.add_dissipated(before - rec_.energy(y));
  }
  // How far a resting contact's gap may stray by the flight's error: 100 times what its positions
  // resolve, atol + rtol |x|. A gap is a difference of positions, so at 1 m from the origin and
  // rtol 1e-8 it is known to 1e-8 m, 100 atol: thresholds at that size fired on the error alone.
  double held_resolution(ConstVectorRef y) const {
    return 100 * (opt_.integrator.atol +
                  opt_.integrator.rtol * velocities_.select(0.0, y.array().abs()).maxCoeff());
  }
  long count() const { return count_; }

  // Contact i's gap closed at t: log it, project onto the surface, apply the impulse, and put
  // the contact at rest when the guards say the bounces have accumulated.
  void resolve(std::size_t i, double t, VectorRef y) {
    count_impulse(t);
    const ConstVectorView x(y);  // y as the read-only calls below take it, built once
    const double v_in = model_.gap_rate(i, x);
    // Bodies that touch without approaching and are not pushed together (a cradle's resting
    // balls, no gravity) have a gap of zero to rounding, and an interpolated state (ARKODE's
    // Hermite) rounds it below zero now and then: a root, but no impact. Nothing happens. Nor when
    // they approach only by the rounding of their velocities (balls that a plastic impact left
    // moving together): struck, the rounding never settled (below).
    if (v_in >= -rate_floor_ && numerical_ && !pushed_together(i, x)) return;
    // A located gap root whose rate is not approaching is noise at the flight's resolution: the
    // gap closed again within what the flight knows of it, atol + rtol |x|. Where the contact's
    // cascade was followed down to that resolution (the bounce lower than held_resolution), it
    // rests, as a touching contact under the exact flight does: the rest height (100 atol) misses
    // the rtol part, and a steel ball's Zeno tail under CVODE at rtol 1e-5 (a 0.0018 m/s bounce,
    // 1.6e-7 m high, against gaps known to 1e-5 m) ended the run. A first contact, or a bounce
    // the flight does resolve, is an error that names the tolerance to tighten.
    if (v_in >= 0 && numerical_ && (last_[i] == -kInf || !(bounce_height(i, x) < held_resolution(x)))) {
      const double resolved = held_resolution(x) / 100;
      throw SolverFailure(
          Status::Unresolved, t,
          fmt::format("contact {} was located with gap rate {:.3g} m/s (not approaching): the "
                      "bounce is below what the flight resolves, atol + rtol |x| = {:.3g} m (atol = "
                      "{:g}, rtol = {:g}); tighten the {} tolerance or raise the rest height ({:g} m)",
                      i, v_in, resolved, opt_.integrator.atol, opt_.integrator.rtol,
                      resolved > 2 * opt_.integrator.atol ? "relative" : "absolute", rest_height_));
    }
    rec_.contact_begin(i, t, v_in);
    rec_.observe_penetration(i, -model_.gap(i, x));
    model_.project(i, y);
    const bool unresolved = v_in >= 0;  // exact flight: touching without approach
    const double before = rec_.energy(x);
    if (!unresolved) {
      const double J = model_.apply_impulse(i, model_.restitution(i), y);
      // An impulse beyond the doubles (a 1e308 kg ball's first, 8e308 N s) ends the run here; the
      // closed-form flight would carry its inf on as a success (solve() would end it at the next
      // sample). J alone is checked: 5 instructions an impact (callgrind), the whole state 19 (2.3 %).
      if (!std::isfinite(J))
        throw SolverFailure(Status::NonFiniteState, t,
                            fmt::format("contact {}'s impulse ({:.3g} N s) left the state not finite", i, J));
    }
    const double v_out = model_.gap_rate(i, x);
    // Resting by height stops a decaying cascade that was followed down to the flight's
    // resolution. A first bounce already that low, or one that does not decay (e = 1), was never
    // resolved: resting there would drop its energy silently. Unless the impact itself stopped a
    // resolved approach (e = 0, a plastic impact: it leaves slower than the rest speed what came
    // in faster): that bounce is low by the physics, and resting drops no energy the law kept.
    const bool low = !unresolved && bounce_height(i, x) < rest_height_;
    const bool stopped = v_out < opt_.rest_speed && -v_in >= opt_.rest_speed;
    if (low && !stopped && (last_[i] == -kInf || !(v_out < -v_in)))
      throw SolverFailure(
          Status::Unresolved, t,
          fmt::format("contact {}'s bounce rises {:.3g} m, below the {:g} m the flight resolves at "
                      "atol = {:g}, and it is {}: tighten the absolute tolerance",
                      i, bounce_height(i, x), rest_height_, opt_.integrator.atol,
                      last_[i] == -kInf ? "the contact's first" : "not decaying"));
    const bool slow = unresolved || v_out < opt_.rest_speed || low;
    const bool crowded = t - last_[i] < opt_.min_event_spacing;
    rec_.contact_end(i, t, v_out);
    // Only bodies that the free flight pushes into each other come to rest: two balls that leave
    // an impact together (a dropped column, e = 1) fly on as they are. Rested, the upper one was
    // held in mid-air at its speed while the lower flew, and the energy ledger ran off by 60 times
    // the drop's energy.
    if ((slow || crowded) && pushed_together(i, x)) {
      model_.settle(i, y);
      modes_[i] = ContactMode::Resting;
    }
    rec_.add_dissipated(before - rec_.energy(x));  // the impulse's loss, and the final stop
    last_[i] = t;
  }

  // Contacts that start closed (gap <= 0), still (|gap rate| <= the rest speed) and pushed together
  // by the free flight (the gap's acceleration < 0) start at rest: a ball released on the floor, a
  // column of balls. Without this their first impact came after ~1e-26 s of sinking, with a bounce
  // far below what the flight resolves, and the run ended unresolved. The flight is looked ahead
  // again after each (a ball on a held one is pushed into it only once that one is held), and the
  // scan repeats until a pass rests none: at most one pass per contact, one right-hand side per
  // pass and per rest, so a chain of touching balls at rest costs one right-hand side, not one per
  // contact.
  void rest_initial_contacts(VectorRef y) {
    for (bool again = true; again;) {
      again = false;
      look_ahead(y);
      for (std::size_t i = 0; i < model_.contact_count(); ++i) {
        const double rate = model_.gap_rate(i, y);
        if (resting(i) || model_.gap(i, y) > 0 || std::abs(rate) > opt_.rest_speed ||
            !(gap_acceleration(i, y) < 0))
          continue;
        rec_.contact_begin(i, 0.0, rate);
        const double before = rec_.energy(y);
        model_.settle(i, y);
        modes_[i] = ContactMode::Resting;
        rec_.contact_end(i, 0.0, model_.gap_rate(i, y));
        rec_.add_dissipated(before - rec_.energy(y));
        again = true;
        look_ahead(y);
      }
    }
  }

  // Contact `first` closed at t. Impulses are resolved one contact at a time (the sequential
  // rule): the contacts are swept in index order (reversed with reverse_order), and each that still
  // touches (gap <= 0) and approaches takes its impulse, over and over until a sweep resolves none:
  // Gauss–Seidel, as engines' sequential impulses. A row of touching balls thus passes an impulse
  // down the chain within one instant, as in Newton's cradle. The result depends on the order when
  // contacts share a body; experiments measure that rather than hide it. Rescanning from the first
  // contact after every impulse (as before) took exponentially many in a plastic chain, which
  // passes each impulse back and forth: 4953 impulses for five balls, over the million-impact limit
  // for eight, against 249 and 1112 by sweeps.
  // A resting contact that an impulse drives together faster than the rest speed takes its impact
  // too and leaves rest (until its own bounces are slow enough): the support passes the impulse on,
  // as when a ball lands on one resting on the floor. Skipped, the resting ball kept the velocity
  // the impulse gave it without moving, and the contact above it closed again with a gap rate that
  // said it separated (a dropped column of two, e = 0.5, ended unresolved).
  // A free contact approaches when its gap rate is below -kRateRounding times the fastest speed of
  // the instant: its largest approach or the state's largest velocity, whichever is more. A plastic
  // impulse leaves the pair's rate at zero only to rounding, and one left at -6.9e-18 m/s after an
  // approach at 0.65 m/s (a wedge of small balls, e = 0, under GSL's flights) was struck again and
  // again, each impulse lost to the same rounding, until the impact limit; so was a 3-D cradle
  // at elasticity 0 whose balls, moving together at 0.2 m/s, met at a root with a rounding
  // approach of 5.5e-17 m/s, the fastest of that instant. 1e-12 is 1e4 times that rounding, and a
  // speed no contact here resolves.
  static constexpr double kRateRounding = 1e-12;
  // Gaps that close at one instant in exact arithmetic close a rounding apart in floating point.
  // Moving the wedge at 1 m/s (the same motion) put the root of the striker's second ball 1.6e-17
  // s after the first's, its gap 1.4e-17 m at the first (an ulp or two of the 0.05 m coordinates):
  // two instants, so rounding decided which ball took its impulse first, not the sweep's order, and
  // event-ode-reversed gave event-ode's answer, mirrored. A gap within kGapRounding of the positions'
  // size is closed at this instant: some 50 ulps of the coordinates, far below any length a flight
  // resolves.
  static constexpr double kGapRounding = 1e-14;
  void resolve_from(std::size_t first, double t, VectorRef y) {
    instant_start_ = count_;
    const ConstVectorView x(y);  // y as the read-only calls below take it, built once
    rate_floor_ = kRateRounding * std::max(std::abs(model_.gap_rate(first, x)),
                                           velocities_.select(x.array().abs(), 0.0).maxCoeff());
    // One contact: the impulse has nowhere to go on to (it leaves separating or at rest), and no
    // other closes with it (the positions' size is not taken: 5 % of the exact bounces'
    // instructions, callgrind).
    const bool others = model_.contact_count() > 1;
    if (others) closed_gap_ = kGapRounding * velocities_.select(0.0, x.array().abs()).maxCoeff();
    resolve(others ? leading(first, x) : first, t, y);
    for (bool again = others; again;) {
      again = false;
      const std::size_t n = model_.contact_count();
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t j = opt_.reverse_order ? n - 1 - k : k;
        if (model_.gap(j, x) > closed_gap_) continue;  // the gap first: most contacts are apart
        const double rate = model_.gap_rate(j, x);
        if (resting(j) ? rate < -opt_.rest_speed : rate < -rate_floor_) {
          modes_[j] = ContactMode::Free;
          rate_floor_ = std::max(rate_floor_, -kRateRounding * rate);
          resolve(j, t, y);
          again = true;
        } else if (resting(j) && rate < -rate_floor_) {
          // Driven together slower than the rest speed, a resting contact stays at rest and passes
          // the impulse on to its support: settled again, its loss booked. Left alone, the rested
          // ball kept that approach in its frozen state (a dropped column of four, e = 0.5, came to
          // rest with velocities of -8e-8 ... -2.3e-7 m/s).
          count_impulse(t);
          const double before = rec_.energy(y);
          model_.settle(j, y);
          rec_.add_dissipated(before - rec_.energy(y));
          again = true;
        }
      }
    }
    if (others) rest_unresolved_hops(t, y);
    // An impulse that drives a resting contact apart (a ball at rest on the floor struck below its
    // centre) lifts the body off its support. Left at rest, the support went on taking its weight:
    // the ball rose at its lifted speed without slowing, and the ledger ended at 2.6 times the
    // scene's energy.
    for (std::size_t j = 0; j < model_.contact_count(); ++j)
      if (resting(j) && model_.gap_rate(j, x) > opt_.rest_speed) leave_rest(j, y);
  }

 private:
  // The contact that takes the instant's first impulse: the first in the sweep's order among
  // `first` (the located root) and the free contacts closed with it and approaching.
  std::size_t leading(std::size_t first, ConstVectorRef x) const {
    const std::size_t n = model_.contact_count();
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t j = opt_.reverse_order ? n - 1 - k : k;
      if (j == first) break;
      if (!resting(j) && model_.gap(j, x) <= closed_gap_ && model_.gap_rate(j, x) < -rate_floor_) return j;
    }
    return first;
  }

  // Rest is decided at each impulse, on the flight as it is then: a ball that leaves the one below
  // it slowly while that one still flies is not pushed into it, and stays free; once a later
  // impulse of the instant stops the one below on the floor, it is, and its hop (1e-5 m/s, 5e-12 m)
  // is far below what the flight resolves: the run ended unresolved at the next root (12 of 795
  // random dropped columns). So after the sweeps, every closed contact whose hop the flight
  // could not resolve rests: one parting slower than the rest speed, or too slowly to rise above
  // the rest height, that the flight pushes together. Settling it (no relative motion: the pair's
  // mean velocity) lifts a held ball below it as slowly, a resting contact whose hop is as
  // unresolvable: settled again, over and over, each settle taking energy, until none is left.
  void rest_unresolved_hops(double t, VectorRef y) {
    const ConstVectorView x(y);
    for (bool again = true; again;) {
      again = false;
      for (std::size_t j = 0; j < model_.contact_count(); ++j) {
        if (model_.gap(j, x) > closed_gap_) continue;
        const double rate = model_.gap_rate(j, x);
        const ContactMode mode = modes_[j];
        if (!(rate > (mode == ContactMode::Resting ? rate_floor_ : -rate_floor_))) continue;
        modes_[j] = ContactMode::Free;  // the hop is a free flight
        const bool hop =
            pushed_together(j, x) && (rate < opt_.rest_speed || bounce_height(j, x) < rest_height_);
        modes_[j] = mode;
        if (!hop) continue;
        count_impulse(t);
        const double before = rec_.energy(x);
        model_.settle(j, y);
        modes_[j] = ContactMode::Resting;
        rec_.add_dissipated(before - rec_.energy(x));
        again = true;
      }
    }
  }

  // Every impulse counts against the cap, whose message says how many came at one instant.
  void count_impulse(double t) {
    if (++count_ > opt_.max_events)
      throw SolverFailure(
          Status::ZenoLimit, t,
          fmt::format("more than {} impacts before rest ({} of them at this instant, among simultaneous "
                      "contacts); raise the impact limit (max_events) or the rest speed",
                      opt_.max_events, count_ - instant_start_));
  }

  // y_ahead_ = y + h y' along the free flight (the contacts' current modes), h = 1e-6 s: what
  // gap_acceleration() reads.
  static constexpr double kAhead = 1e-6;
  void look_ahead(ConstVectorRef y) {
    model_.rhs(0.0, y, modes_, ydot_);
    y_ahead_ = y + kAhead * ydot_;
  }

  // The gap's acceleration in free flight from the last look_ahead(y), d/dt gap_rate =
  // (gap_rate(y + h y') - gap_rate(y)) / h. The gap rate is linear in the velocities, and y'
  // changes them at the rate of the applied forces, so for a ball the quotient is exactly -g;
  // h = 1e-6 s keeps the error from rotating normals at O(h).
  double gap_acceleration(std::size_t i, ConstVectorRef y) const {
    return (model_.gap_rate(i, y_ahead_) - model_.gap_rate(i, y)) / kAhead;
  }

  // Whether the free flight accelerates contact i's bodies into each other at y.
  bool pushed_together(std::size_t i, ConstVectorRef y) {
    look_ahead(y);
    return gap_acceleration(i, y) < 0;
  }

  // How high the bounce leaving at y rises: v^2 / (2 |a|), a the gap's acceleration, formed as
  // v (v / 2|a|): v^2 underflowed to 0 for a drop of 1e-165 m (speeds of 1e-165 m/s), whose first
  // bounce then rose '0 m' and ended the run unresolved.
  double bounce_height(std::size_t i, ConstVectorRef y) {
    if (rest_height_ <= 0) return kInf;
    look_ahead(y);
    const double v = model_.gap_rate(i, y), a = gap_acceleration(i, y);
    return a < 0 ? v * (v / (-2 * a)) : kInf;
  }

  const MechanicalSystem& model_;
  const EventOptions& opt_;
  RunRecorder& rec_;
  bool numerical_;
  double rest_height_;
  Mask velocities_;          // the state's velocity entries
  double rate_floor_ = 0.0;  // approaches slower than this are rounding (resolve_from)
  double closed_gap_ = 0.0;  // gaps below this are closed at the instant (resolve_from)
  long instant_start_ = 0;   // count_ when this instant's impulses began
  ContactModes modes_;
  std::vector<double> last_;
  Vector ydot_, y_ahead_;
  long count_ = 0;
};

}  // namespace

RunResult run_event_driven(const MechanicalSystem& model, const EventOptions& opt, const SolveOptions& span) {
  const std::size_t nc = model.contact_count();
  RunRecorder rec(model, "event-driven " + opt.integrator.method, span);
  // Rigid bodies have no springs: the scene's spring energy at an overlap of rounding size was
  // counted (touching balls at k = 1e300: 3e268 J of a 0.05 J cradle), whatever the law's k.
  rec.exclude_spring_energy();
  Impacts impacts(model, opt, rec, true);

  OdeSystem sys =
      mechanical_ode(model, [&](ConstVectorRef) -> const ContactModes& { return impacts.modes(); });
  // Per contact: the gap (impact) and the gap rate (apex), both on falling zeros only. A resting
  // contact's are its gap against the flight's resolution (held_resolution): the first fires when
  // a body its support holds has sunk half of it into the support, the second when the bodies
  // have parted by all of it (a ball that a curved support lets go of). Both held at 1, such a
  // ball flew on with the support still taking its weight, and one sliding on sank by the flight's
  // error until the run ended. Parting is read off the gap, not its rate, which parts by the
  // flight's error too. Moving bodies marked at rest are not held (holds_at_rest): pressing on,
  // they end the run at a sample (below), as before.
  sys.root_count = 2 * nc;
  std::vector<double> gaps(nc), rates(nc);
  const double touch_offset = contact::touch_offset(opt.integrator);
  sys.roots = [&](double, ConstVectorRef y, VectorRef g) {
    model.gaps_and_rates(y, gaps, rates);
    double resolution = -1;  // taken once, and only where a contact rests
    for (std::size_t i = 0; i < nc; ++i) {
      const auto at = static_cast<Eigen::Index>(2 * i);
      if (impacts.resting(i)) {
        if (resolution < 0) resolution = impacts.held_resolution(y);
        g[at] = model.holds_at_rest(i) ? gaps[i] + resolution / 2 : 1.0;
        g[at + 1] = resolution - gaps[i];
        continue;
      }
      g[at] = gaps[i] + touch_offset;  // touching but not yet approaching still counts as apart
      g[at + 1] = rates[i];
    }
  };
  EventHandling drive;
  // Gaps on falling zeros only. Rates on both: falling for the apex (or a resting contact's
  // parting), rising for the closest approach. Bodies small for their speed pass through each
  // other within one step, their gap negative only between its ends: a cue ball of radius 2.3e-6 m
  // went through the red one at 2 m/s (4.6 us of a 5 ms step), 'success' with no contact, when
  // only falling rates were roots. The rate turns from approach to parting within the step, at
  // the centres' crossing or a graze's closest approach, and the root search that brackets it
  // meets the overlap and locates the entry, the earliest root. Should it not, the closest
  // approach itself finds the overlap, and the run ends as a sample finding one would (below).
  drive.root_directions.assign(2 * nc, -1);
  for (std::size_t i = 0; i < nc; ++i) drive.root_directions[2 * i + 1] = 0;
  const double overlap_limit = 100 * opt.integrator.atol;  // what the flight resolves (below)
  drive.on_roots = [&](double t, Vector& y, const std::vector<int>& roots) {
    for (std::size_t i = 0; i < nc; ++i)
      if (roots[2 * i + 1] > 0 && !impacts.resting(i) && model.gap(i, y) < -overlap_limit)
        throw unlocated_overlap(i, t, model.gap(i, y));
    bool impact = false, rest_changed = false;
    for (std::size_t k = 0; k < nc; ++k) {
      const std::size_t i = opt.reverse_order ? nc - 1 - k : k;
      if (roots[2 * i + 1] < 0 && impacts.resting(i)) {
        impacts.leave_rest(i, y);
        rest_changed = true;
      } else if (roots[2 * i + 1] < 0) {
        rec.apex(i, t, model.gap(i, y), rec.energy(y));
      }
      if (roots[2 * i] != 0 && impacts.resting(i)) {
        impacts.resettle(i, y);
        rest_changed = true;
      } else if (roots[2 * i] != 0 && !impact) {
        impacts.resolve_from(i, t, y);
        impact = true;
      }
    }
    return impact || rest_changed;
  };
  // Bodies that leave a plastic impact together and go on pressing into each other (a ball that
  // strikes a free cuboid off its centre, e = 0: the cuboid turns away under the contact point)
  // overlap with no root to locate, the gap having left zero downwards at the restart: the ball
  // passed into the cuboid and the run ended 'success', its energy (the overlap's spring) 700 times
  // the initial (the contact had been put at rest: the cuboid's turn pushes the gap down, but
  // nothing holds a free body). Impulses do not model a sustained contact between free bodies; a
  // sample that finds an overlap beyond the flight's resolution (100 atol; a resting contact's own,
  // held_resolution) ends the run.
  drive.sample = [&](double t, ConstVectorRef y) {
    for (std::size_t i = 0; i < nc; ++i) {
      const bool held = impacts.resting(i) && model.holds_at_rest(i);
      const double limit = held ? impacts.held_resolution(y) : overlap_limit;
      if (model.gap(i, y) >= -limit) continue;
      if (t == 0.0)  // a scene whose bodies start inside each other (a large radius)
        throw SolverFailure(Status::Unresolved, t,
                            fmt::format("contact {} overlaps by {:.3g} m at the start: impulses need the "
                                        "bodies apart or touching",
                                        i, -model.gap(i, y)));
      throw unlocated_overlap(i, t, model.gap(i, y));
    }
    rec.sample(t, y);
  };
  Vector y0 = model.initial_state();
  impacts.rest_initial_contacts(y0);
  return contact::drive(std::move(sys), y0, opt.integrator, rec, drive);
}

RunResult run_event_driven(const MechanicalSystem& model, const AnalyticFlight& flight,
                           const EventOptions& opt, const SolveOptions& span) {
  const std::size_t nc = model.contact_count();
  RunRecorder rec(model, "event-driven exact", span);
  rec.exclude_spring_energy();  // no springs (above)
  Impacts impacts(model, opt, rec, false);

  // Every state on a flight leg is computed from the leg's start with a time measured from it
  // (never t - t_leg, which would lose the leg time's low bits to the absolute time), so samples
  // and apexes do not perturb the trajectory and impacts land on the surface to rounding.
  double t_leg = 0.0, tau_now = 0.0;  // leg start, and the current time measured from it
  Vector y_leg = model.initial_state();
  impacts.rest_initial_contacts(y_leg);
  Vector y = y_leg;
  // Read-only views of the two states, built once: handed the vectors, the calls below built a
  // temporary view each, 13 an impact (a tenth of its instructions). Both keep their storage: they
  // are only ever assigned states of their own size.
  const ConstVectorView leg(y_leg), now(y);
  bool any_rest =
      std::ranges::any_of(impacts.modes(), [](ContactMode m) { return m == ContactMode::Resting; });
  // Each contact's impact and apex times on the current leg, computed once per leg (the leg's
  // outputs and apexes do not change them).
  std::vector<double> leg_impact(nc), leg_apex(nc);
  const auto start_leg = [&] {
    for (std::size_t i = 0; i < nc; ++i) {
      leg_impact[i] = flight.time_to_impact(i, leg);
      leg_apex[i] = flight.time_to_apex(i, leg);
    }
  };
  start_leg();

  SolverStats own;
  double t = 0.0;
  try {
    // A contact that starts closed and approaching (a ball thrown down from the floor) strikes at
    // t = 0. The legs look for impacts strictly after their start, so the ball fell through the
    // floor and the run 'succeeded' (47 m down after 3 s, E + D off by 2e8 times E0).
    for (std::size_t i = 0; i < nc; ++i) {
      if (impacts.resting(i) || model.gap(i, leg) > 0 || !(model.gap_rate(i, leg) < 0)) continue;
      impacts.resolve_from(i, 0.0, y_leg);
      any_rest = impacts.resting(i);
      y = y_leg;
      start_leg();
      own.events += 1;
      break;
    }
    for (double t_out = rec.next_sample_time(); std::isfinite(t_out); t_out = rec.next_sample_time()) {
      throw_if_stop_requested(t);
      // The earliest of: the next output, an impact, an apex (times from the leg's start).
      double tau = t_out - t_leg;
      std::size_t which = nc;
      bool impact = false;
      for (std::size_t i = 0; i < nc && !any_rest; ++i) {
        const double ti = leg_impact[i], ta = leg_apex[i];
        if (ta > tau_now && ta < tau) {
          tau = ta;
          which = i;
          impact = false;
        }
        if (ti > tau_now && ti <= tau) {
          tau = ti;
          which = i;
          impact = true;
        }
      }
      t = which == nc ? t_out : t_leg + tau;
      tau_now = tau;
      if (any_rest)
        y = y_leg;
      else
        flight.propagate(leg, tau, y);
      if (which == nc) {
        rec.sample(t, now);
      } else if (impact) {
        impacts.resolve_from(which, t, y);
        any_rest = impacts.resting(which);
        t_leg = t;
        tau_now = 0.0;
        y_leg = y;
        start_leg();
        own.steps += 1;
        own.events += 1;
      } else {
        rec.apex(which, t, model.gap(which, now), rec.energy(now));
        own.events += 1;
      }
    }
  } catch (const SolverFailure& f) {
    return rec.fail(f, own);
  }
  return rec.finish(own, t);
}

}  // namespace contact

namespace contact {

std::vector<MethodInfo> event_methods() {
  auto options = [](const Method& m, bool reverse) {
    return EventOptions{.integrator = m.integrator,
                        .rest_speed = m.rest_speed,
                        .rest_height = m.rest_height,
                        .min_event_spacing = m.min_event_spacing,
                        .max_events = m.max_events,
                        .reverse_order = reverse};
  };
  std::vector<std::string> settings = kIntegratorSettings;  // the flight's integrator, and the guard
  settings.push_back("rest_speed");
  settings.push_back("rest_height");
  settings.push_back("max_events");
  auto numerical = [options, settings](std::string name, std::string description, bool reverse) {
    return MethodInfo{
        .name = std::move(name),
        .description = std::move(description),
        .family = "event-driven",
        .fixed_step = false,
        .uses_contact_law = false,
        .needs = "dynamics, contact geometry and an impulse map",
        .can_run =
            [](const Dynamics& scene) { return dynamic_cast<const MechanicalSystem*>(&scene) != nullptr; },
        .run =
            [options, reverse](const Dynamics& scene, const Method& m, const SolveOptions& span) {
              return run_event_driven(dynamic_cast<const MechanicalSystem&>(scene), options(m, reverse),
                                      span);
            },
        .settings = settings,
        .working_doubles = kIntegratorWorkingDoubles};
  };
  auto exact = [](const Dynamics& scene) {
    return dynamic_cast<const MechanicalSystem*>(&scene) != nullptr &&
           dynamic_cast<const AnalyticFlight*>(&scene) != nullptr;
  };
  return {
      numerical("event-ode",
                "event-driven impulses, flight integrated with root finding, lowest contact first", false),
      numerical("event-ode-reversed", "as event-ode, highest contact first (the sequential rule's order)",
                true),
      MethodInfo{.name = "event-exact",
                 .description = "event-driven impulses, the scene's closed-form flight (reference)",
                 .family = "event-driven",
                 .fixed_step = false,
                 .uses_contact_law = false,
                 .needs = "a closed-form free flight (AnalyticFlight) besides an impulse map",
                 .can_run = exact,
                 .run =
                     [options](const Dynamics& scene, const Method& m, const SolveOptions& span) {
                       return run_event_driven(dynamic_cast<const MechanicalSystem&>(scene),
                                               dynamic_cast<const AnalyticFlight&>(scene), options(m, false),
                                               span);
                     },
                 .settings = {"rest_speed", "rest_height", "max_events"}}};
}

}  // namespace contact
