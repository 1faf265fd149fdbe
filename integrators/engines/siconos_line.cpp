#include "siconos_line.hpp"

#include <SiconosKernel.hpp>
#include <boost/exception/diagnostic_information.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace contact {

namespace {

// Siconos keeps event times as whole numbers of ticks of 1e-16 s in GMP integers, converted from
// doubles: a time beyond DBL_MAX ticks is a floating-point exception (SIGFPE), not an error.
constexpr double kLatestTime = 1e290;
constexpr long kMaxEvents = 1'000'000, kEventsJudged = 10'000;  // in one step
constexpr const char* kClockRange = "its clock counts ticks of 1e-16 s and ends near 1e292 s";

// Siconos throws boost exceptions whose what() is only "std::exception": its message is one of
// the tags of the diagnostic information, beside an errno left over from whatever call set it last
// ("Inappropriate ioctl for device"), which says nothing of the failure. The message alone, on one
// line; the whole information when it has none.
std::string siconos_message() {
  std::string text = boost::current_exception_diagnostic_information(false);
  std::replace(text.begin(), text.end(), '\n', ' ');
  const std::string tag = "[Siconos::message*] = ";
  const auto at = text.find(tag);
  if (at != std::string::npos) text = text.substr(at + tag.size());
  text.erase(text.find_last_not_of(' ') + 1);
  return text;
}

// Siconos prints a failing interaction's state on std::cout before it throws: that would land in
// the middle of an experiment's output. Held aside while Siconos runs; the exception says what
// failed.
class QuietStdout {
 public:
  QuietStdout() : saved_(std::cout.rdbuf(held_.rdbuf())) {}
  ~QuietStdout() { std::cout.rdbuf(saved_); }
  QuietStdout(const QuietStdout&) = delete;
  QuietStdout& operator=(const QuietStdout&) = delete;

 private:
  std::ostringstream held_;
  std::streambuf* saved_;
};

}  // namespace

struct SiconosLine::State {
  SiconosSpheres spheres;
  std::vector<SP::LagrangianLinearTIDS> bodies;
  std::vector<SP::Interaction> contacts;
  SP::NonSmoothDynamicalSystem nsds;
  SP::EventDriven simulation;
  std::vector<double> impulse;
  std::vector<double> centre_before, velocity_before, in_event;  // an event's, for the observer
};

SiconosLine::SiconosLine(const SiconosSpheres& sp) : s_(std::make_unique<State>()) {
  // Its initialisation prints too when it fails (a stack dropped from 3e9 m, whose gaps round
  // below its tolerance): some 40 lines on the caller's standard output, beside a typed error.
  const QuietStdout quiet;
  // Siconos's LCP solver asserts, aborting the process, where a weight is infinite (a stack of
  // 3e307 kg balls: m g overflows); every body's numbers are checked first.
  for (std::size_t b = 0; b < sp.mass.size(); ++b) {
    const double weight = sp.vertical ? sp.mass[b] * sp.g : 0.0;
    if (!(std::isfinite(sp.mass[b]) && std::isfinite(weight) && std::isfinite(sp.centre[b]) &&
          std::isfinite(sp.velocity[b])))
      throw std::runtime_error(fmt::format(
          "Siconos cannot take body {}: its mass {:g} kg, weight {:g} N, centre {:g} m and velocity "
          "{:g} m/s have to be finite",
          b, sp.mass[b], weight, sp.centre[b], sp.velocity[b]));
  }
  s_->spheres = sp;
  const double t_far = 1e9;  // the run ends when the caller stops stepping
  auto nsds = s_->nsds = std::make_shared<NonSmoothDynamicalSystem>(0.0, t_far);
  for (std::size_t b = 0; b < sp.mass.size(); ++b) {
    auto q0 = std::make_shared<SiconosVector>(1), v0 = std::make_shared<SiconosVector>(1);
    (*q0)(0) = sp.centre[b];
    (*v0)(0) = sp.velocity[b];
    auto mass = std::make_shared<SimpleMatrix>(1, 1);
    (*mass)(0, 0) = sp.mass[b];
    auto body = std::make_shared<LagrangianLinearTIDS>(q0, v0, mass);
    auto weight = std::make_shared<SiconosVector>(1);
    (*weight)(0) = sp.vertical ? -sp.mass[b] * sp.g : 0.0;
    body->setFExtPtr(weight);
    nsds->insertDynamicalSystem(body);
    s_->bodies.push_back(body);
  }
  for (std::size_t c = 0; c < sp.restitution.size(); ++c) {
    const bool on_floor = sp.floor && c == 0;
    // The gap: centre - r above the floor, or x_b - x_a - 2r between neighbours a and b.
    auto H = std::make_shared<SimpleMatrix>(1, on_floor ? 1 : 2);
    auto offset = std::make_shared<SiconosVector>(1);
    if (on_floor) {
      (*H)(0, 0) = 1.0;
      (*offset)(0) = -sp.radius;
    } else {
      (*H)(0, 0) = -1.0;
      (*H)(0, 1) = 1.0;
      (*offset)(0) = -2 * sp.radius;
    }
    auto inter = std::make_shared<Interaction>(std::make_shared<NewtonImpactNSL>(sp.restitution[c]),
                                               std::make_shared<LagrangianLinearTIR>(H, offset));
    const std::size_t upper = sp.floor ? c : c + 1;
    if (on_floor)
      nsds->link(inter, s_->bodies[upper]);
    else
      nsds->link(inter, s_->bodies[upper - 1], s_->bodies[upper]);
    s_->contacts.push_back(inter);
  }
  if (!(sp.dt < kLatestTime))
    throw std::runtime_error(fmt::format("Siconos cannot step by {:g} s: {}", sp.dt, kClockRange));
  auto osi = std::make_shared<LsodarOSI>();
  osi->setTol(1, sp.rtol, sp.atol);
  s_->simulation = std::make_shared<EventDriven>(nsds, std::make_shared<TimeDiscretisation>(0.0, sp.dt));
  s_->simulation->insertIntegrator(osi);
  // The gap below which Siconos counts a contact closed (its default 2.2e-12) has to exceed the
  // error of a located landing: a gap below minus it at the next bounce, shorter than the
  // tolerance near the Zeno time, was "output of level 0 must be positive" and the end of the run
  // (e = 0.3 and 0.606 at 1e-12). Ten times atol still failed 54 of 120 random drops (h0 1 mm to
  // 100 m, g 0.1 to 50 m/s^2) near their Zeno times; a hundred times runs all of them and 200
  // more, the apexes unchanged. A static of Siconos, the same for every simulation here.
  s_->simulation->setToleranceED(100 * sp.atol);
  s_->simulation->insertNonSmoothProblem(std::make_shared<LCP>(), SICONOS_OSNSP_ED_IMPACT);
  s_->simulation->insertNonSmoothProblem(std::make_shared<LCP>(), SICONOS_OSNSP_ED_SMOOTH_ACC);
  try {
    s_->simulation->initialize();
  } catch (...) {
    throw std::runtime_error("Siconos could not initialise the simulation: " + siconos_message());
  }
  s_->impulse.assign(sp.restitution.size(), 0.0);
  s_->in_event.assign(sp.restitution.size(), 0.0);
}

// Siconos's topology graphs hold its systems, interactions and integrator in shared_ptr cycles:
// taking the interactions and systems out of the system breaks them, so that nothing leaks.
SiconosLine::~SiconosLine() {
  try {
    for (auto& inter : s_->contacts) s_->nsds->removeInteraction(inter);
    for (auto& body : s_->bodies) s_->nsds->removeDynamicalSystem(body);
  } catch (...) {  // a destructor does not throw; what is left is only memory
  }
}

void SiconosLine::step(double h, const std::function<void(double t)>& checkpoint,
                       const ImpactObserver& at_impact) {
  EventDriven& sim = *s_->simulation;
  std::fill(s_->impulse.begin(), s_->impulse.end(), 0.0);
  const double start = sim.startingTime(), dt = s_->spheres.dt, target = start + h * (1 - 1e-9);
  if (!(start + h + dt < kLatestTime))
    throw std::runtime_error(fmt::format("Siconos cannot reach t = {:g} s: {}", start + h + dt, kClockRange));
  // A step below Siconos's clock tick (a span of 1e-300 s) cannot be an event of its own (it fell on
  // the step's start, and the state read back was NaN): the state moves by less than its speed
  // times 1e-16 s, so it stays.
  if (h < 10 * DEFAULT_TICK) return;
  const QuietStdout quiet;
  try {
    // Siconos stops only at its events: its time discretisation's every dt, and the impacts. A run's
    // last step, shorter than dt, gets an event of its own at its end. EventsManager::insertEvent
    // places a time-discretisation event at the discretisation's instant of the manager's current
    // index k (the instants so far are 0, dt, ..., k dt), so the one given starts k steps earlier.
    if (h < dt * (1 - 1e-9)) {
      EventsManager& events = *sim.eventsManager();
      const double k = std::round(events.getTk() / dt);
      events.insertEvent(TD_EVENT, std::make_shared<TimeDiscretisation>(start + h - k * dt, dt));
    }
    for (long events = 0; sim.nextTime() <= target + h * 1e-6; ++events) {
      if (events > kMaxEvents)
        throw std::runtime_error("more than a million events in one step at t = " +
                                 std::to_string(sim.startingTime()));
      const double t0 = sim.startingTime();
      sim.advanceToEvent();
      if (at_impact) read(s_->centre_before, s_->velocity_before);  // an event changes no position
      sim.processEvents();
      const double held = sim.startingTime() - t0;
      bool impact = false;
      for (std::size_t c = 0; c < s_->contacts.size(); ++c) {
        const Interaction& inter = *s_->contacts[c];
        s_->in_event[c] = inter.lambda(1)->getValue(0);  // an impact's impulse, 0 otherwise
        impact = impact || s_->in_event[c] > 0;
        s_->impulse[c] += s_->in_event[c];
        if (inter.lambda(2)) s_->impulse[c] += inter.lambda(2)->getValue(0) * held;  // resting force
      }
      if (impact && at_impact) at_impact(s_->centre_before, s_->velocity_before, s_->in_event);
      if (sim.startingTime() >= target) break;
      // A chatter Siconos does not end (a column of 1e-30 kg balls: an impact every 4e-11 s, 2.4e7
      // for a 1 ms step) ran into the bound above only after a minute, Ctrl-C unheard: judged at
      // 1e4 events by the time they covered, and the caller looks in (a stop request) every 1000.
      if (checkpoint && events % 1000 == 999) checkpoint(sim.startingTime());
      if (events == kEventsJudged) {
        const double covered = sim.startingTime() - start,
                     needed = (target - start) / covered * kEventsJudged;
        if (!(needed <= kMaxEvents))
          throw std::runtime_error(fmt::format(
              "Siconos took {} events to cover {:.3g} s of a {:.3g} s step at t = {:g} s: about {:.3g} "
              "for the step, more than the {} a step may take (impacts it does not bring to rest)",
              kEventsJudged, covered, h, start, needed, kMaxEvents));
      }
    }
  } catch (const std::runtime_error&) {
    throw;
  } catch (...) {
    throw std::runtime_error("Siconos at t = " + std::to_string(sim.startingTime()) + ": " +
                             siconos_message());
  }
}

void SiconosLine::read(std::vector<double>& centre, std::vector<double>& velocity) const {
  centre.resize(s_->bodies.size());
  velocity.resize(s_->bodies.size());
  for (std::size_t b = 0; b < s_->bodies.size(); ++b) {
    centre[b] = s_->bodies[b]->q()->getValue(0);
    velocity[b] = s_->bodies[b]->velocity()->getValue(0);
  }
}

void SiconosLine::impulses(std::vector<double>& impulse) const { impulse = s_->impulse; }

}  // namespace contact
