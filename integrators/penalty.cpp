#include "penalty.hpp"

#include "integrator_driver.hpp"

#include <cmath>

namespace contact {

RunResult run_penalty(const MechanicalSystem& model, const PenaltyOptions& opt) {
  const std::size_t nc = model.contact_count();
  RunRecorder rec(model, "penalty " + opt.integrator.method, opt.sample_dt, opt.t_end, opt.limits);
  const Vector y0 = model.initial_state();
  ContactModes modes(nc);
  model.modes_from_state(y0, modes);

  // Without located switches the modes follow the state inside every call.
  auto modes_at = [&](ConstVectorRef y) -> const ContactModes& {
    if (!opt.locate_switches) model.modes_from_state(y, modes);
    return modes;
  };
  OdeSystem base = mechanical_ode(model, modes_at);
  const double threshold = contact_threshold(opt.integrator);
  base.root_count = 2 * nc;
  base.roots = [&](double, ConstVectorRef y, VectorRef g) {
    for (std::size_t i = 0; i < nc; ++i) {
      // Touching counts as the mode held (see contact_threshold).
      const double side = modes[i] == ContactMode::Penalty ? threshold : -threshold;
      g[static_cast<Eigen::Index>(2 * i)] = model.switching(i, y) + side;
      g[static_cast<Eigen::Index>(2 * i + 1)] = model.gap_rate(i, y);
    }
  };
  // The energy ledger: the laws' dissipated power integrated as one more state.
  OdeSystem sys = with_ledger(std::move(base), [&](ConstVectorRef y) {
    double p = 0;
    const ContactModes& m = modes_at(y);
    for (std::size_t i = 0; i < nc; ++i)
      if (m[i] == ContactMode::Penalty) p += model.dissipated_power(i, y);
    return p;
  });
  const auto n = static_cast<Eigen::Index>(model.state_size());
  Vector y0_ledger(n + 1);
  y0_ledger << y0, 0.0;

  for (std::size_t i = 0; i < nc; ++i)
    if (modes[i] == ContactMode::Penalty) rec.contact_begin(i, 0.0, model.gap_rate(i, y0));

  EventHandling drive;
  drive.on_roots = [&](double t, Vector& y_full, const std::vector<int>& roots) {
    const auto y = y_full.head(n);
    bool switched = false;
    for (std::size_t i = 0; i < nc; ++i) {
      const int sw = roots[2 * i], rate = roots[2 * i + 1];
      const bool engaged = modes_at(y)[i] == ContactMode::Penalty;
      if (rate > 0 && engaged) rec.observe_penetration(i, -model.gap(i, y));
      if (rate < 0 && !engaged) rec.apex(i, t, model.gap(i, y), model.energy(y), y_full[n]);
      if (sw > 0) rec.contact_begin(i, t, model.gap_rate(i, y));
      if (sw < 0) {
        rec.observe_penetration(i, -model.gap(i, y));
        rec.contact_end(i, t, model.gap_rate(i, y));
      }
      if (sw != 0 && opt.locate_switches) {
        modes[i] = sw > 0 ? ContactMode::Penalty : ContactMode::Free;
        switched = true;
      }
    }
    return switched;
  };
  drive.sample = [&](double t, ConstVectorRef y_full) {
    const auto y = y_full.head(n);
    for (std::size_t i = 0; i < nc; ++i) rec.observe_penetration(i, -model.gap(i, y));
    rec.sample(t, y, y_full[n]);
  };
  return contact::drive(std::move(sys), y0_ledger, opt.integrator, rec, drive);
}

}  // namespace contact
