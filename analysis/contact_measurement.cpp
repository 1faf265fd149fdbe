#include "contact_ode/analysis/contact_measurement.hpp"

#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_drop.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace contact {

SpringContact measure_isolated_contact(const ContactLaw& law, double m, double V, double rtol) {
  // Start just above the floor so the flight in is negligible but non-zero. The time limit covers
  // the slowest contact the laws here produce: the power law's duration estimate times 100.
  const SpringContact undamped = power_law_contact(m, stiffness(law), exponent(law), V);
  const double t_contact = undamped.duration;
  const double h0 = 1e-3 * V * t_contact;
  const double t_end = h0 / V + 100 * t_contact;
  PenaltyOptions o;
  o.integrator.rtol = rtol;
  o.integrator.atol = rtol * 1e-3 * undamped.max_penetration;
  o.integrator.max_steps = 1000000;
  const RunResult r =
      run_penalty(BallDrop({m, 0.0, h0, -V, 1.0, law}), o, {.t_end = t_end, .sample_dt = t_end});
  if (!r.ok()) throw std::runtime_error(fmt::format("contact simulation failed: {}", r.message));
  if (r.contacts.empty() || !r.contacts.front().closed())
    throw ContactDidNotEnd(
        fmt::format("the contact did not end within {:g} s, 100 times the undamped contact's {:g} s: the "
                    "law's damping holds the bodies together ({})",
                    t_end, t_contact, describe(law)));
  const auto& c = r.contacts.front();
  return {c.duration(), c.max_penetration, c.v_out};
}

}  // namespace contact
