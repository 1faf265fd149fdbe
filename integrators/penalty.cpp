#include "penalty.hpp"

#include "run_recorder.hpp"

#include <cmath>

namespace contact {

namespace {

void modes_from_state(const MechanicalSystem& model, ConstVectorRef y, ContactModes& modes) {
  for (std::size_t i = 0; i < modes.size(); ++i)
    modes[i] = model.switching(i, y) > 0 ? ContactMode::Penalty : ContactMode::Free;
}

}  // namespace

RunResult run_penalty(const MechanicalSystem& model, const PenaltyOptions& opt) {
  const std::size_t nc = model.contact_count();
  RunRecorder rec(model, "penalty-cvode", opt.sample_dt, opt.t_end);
  const Vector y0 = model.initial_state();
  ContactModes modes(nc);
  modes_from_state(model, y0, modes);

  // Without located switches the modes follow the state inside every call.
  auto modes_at = [&](ConstVectorRef y) -> const ContactModes& {
    if (!opt.locate_switches) modes_from_state(model, y, modes);
    return modes;
  };
  OdeSystem sys;
  sys.size = model.state_size();
  sys.position_size = model.position_size();
  sys.rhs = [&](double t, ConstVectorRef y, VectorRef yd) { model.rhs(t, y, modes_at(y), yd); };
  sys.jacobian = [&](double t, ConstVectorRef y, MatrixRef J) {
    model.jacobian(t, y, modes_at(y), J);
  };
  sys.root_count = 2 * nc;
  sys.roots = [&](double, ConstVectorRef y, VectorRef g) {
    for (std::size_t i = 0; i < nc; ++i) {
      g[static_cast<Eigen::Index>(2 * i)] = model.switching(i, y);
      g[static_cast<Eigen::Index>(2 * i + 1)] = model.gap_rate(i, y);
    }
  };

  CvodeSolver solver(sys, 0.0, y0, opt.cvode);
  for (std::size_t i = 0; i < nc; ++i)
    if (modes[i] == ContactMode::Penalty) rec.contact_begin(i, 0.0, model.gap_rate(i, y0));

  SolverStats own;  // events handled here; CVODE counts the rest
  double t = 0.0;
  try {
    for (double t_out = rec.next_sample_time(); std::isfinite(t_out); t_out = rec.next_sample_time()) {
      if (t_out > t) {
        const auto out = solver.advance(t_out);
        t = out.t;
        if (out.root) {
          const Vector y = solver.y();
          bool switched = false;
          for (std::size_t i = 0; i < nc; ++i) {
            const int sw = out.roots_found[2 * i], rate = out.roots_found[2 * i + 1];
            const bool engaged = modes_at(y)[i] == ContactMode::Penalty;
            if (rate > 0 && engaged) rec.observe_penetration(i, -model.gap(i, y));
            if (rate < 0 && !engaged) rec.apex(i, t, model.gap(i, y), model.energy(y));
            if (sw > 0) rec.contact_begin(i, t, model.gap_rate(i, y));
            if (sw < 0) {
              rec.observe_penetration(i, -model.gap(i, y));
              rec.contact_end(i, t, model.gap_rate(i, y));
            }
            if (sw != 0 && opt.locate_switches) {
              modes[i] = sw > 0 ? ContactMode::Penalty : ContactMode::Free;
              switched = true;
            }
            own.events += (sw != 0) + (rate != 0);
          }
          if (switched) solver.reinit(t, y);
          continue;
        }
      }
      for (std::size_t i = 0; i < nc; ++i) rec.observe_penetration(i, -model.gap(i, solver.y()));
      rec.sample(t, solver.y());
    }
  } catch (const SolverFailure& f) {
    own += solver.stats();
    return rec.fail(f, own);
  }
  own += solver.stats();
  return rec.finish(own, t);
}

}  // namespace contact
