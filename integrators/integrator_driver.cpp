#include "integrator_driver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace contact {

RunResult drive(OdeSystem system, ConstVectorRef y0, const IntegratorOptions& options, RunRecorder& rec,
                const EventHandling& events) {
  const long root_functions = static_cast<long>(system.root_count);
  std::unique_ptr<Integrator> integrator;
  try {
    integrator = make_integrator(options, std::move(system), 0.0, y0);
  } catch (const SolverFailure& f) {
    return rec.fail(f, SolverStats{});
  }
  if (!events.root_directions.empty()) integrator->set_root_directions(events.root_directions);
  long handled = 0;
  auto stats = [&] {
    SolverStats s = integrator->stats();
    s.events += handled;
    return s;
  };
  double t = 0.0;
  // Progress guard: CVODE can return a root without flagging any (its sign test glo * ghi < 0
  // underflowed for root functions of ~1e-160, which the root callback now compresses out of that
  // range: sundials_callbacks.cpp); calling it again returns the same root forever.
  // Such a return restarts the integrator, which clears its root memory and steps past; a run
  // that still returns at the same time, whatever the reason, ends with Status::NoProgress.
  // Simultaneous roots are reported in one return, so a bound of a few returns per root
  // function at one instant is generous. CVODE also returns a flagged root again at the same t
  // where its function is zero there to the bit (the gap rate of two balls at rest in a column
  // of 200, whose velocities are equal): the same roots returned again at the same time were
  // handled already, and the integrator is restarted past them (a 200-ball column's run ended
  // 'no-progress' after 811 such returns).
  const long max_returns_at_one_time = 2 * root_functions + 10;
  long returns_at_t = 0;
  double t_last_root = -std::numeric_limits<double>::infinity();
  std::vector<int> last_roots;
  try {
    for (double t_out = rec.next_sample_time(); std::isfinite(t_out); t_out = rec.next_sample_time()) {
      throw_if_stop_requested(t);
      if (t_out > t) {
        const auto out = integrator->advance(t_out);
        t = out.t;
        rec.check_steps(integrator->stats().steps, t);
        if (out.root) {
          returns_at_t = t > t_last_root ? 1 : returns_at_t + 1;
          t_last_root = t;
          if (returns_at_t > max_returns_at_one_time)
            throw SolverFailure(
                Status::NoProgress, t,
                fmt::format("the integrator returned {} times at t = {:.17g} without advancing", returns_at_t,
                            t));
          Vector y = integrator->y();
          const auto flagged =
              std::count_if(out.roots_found.begin(), out.roots_found.end(), [](int r) { return r != 0; });
          const bool repeated = returns_at_t > 1 && out.roots_found == last_roots;
          last_roots = out.roots_found;
          if (repeated) {
            integrator->reinit(t, y);
            continue;
          }
          handled += flagged;
          if (flagged == 0 || events.on_roots(t, y, out.roots_found)) integrator->reinit(t, y);
          continue;
        }
      }
      if (events.sample)
        events.sample(t, integrator->y());
      else
        rec.sample(t, integrator->y());
    }
  } catch (const SolverFailure& f) {
    return rec.fail(f, stats());
  }
  return rec.finish(stats(), t);
}

OdeSystem mechanical_ode(const Dynamics& model, ModesAt modes_at) {
  OdeSystem sys;
  sys.size = model.state_size();
  sys.positions = model.position_mask();
  sys.bandwidth = model.jacobian_bandwidth();
  sys.rhs = [&model, modes_at](double t, ConstVectorRef y, VectorRef yd) {
    model.rhs(t, y, modes_at(y), yd);
  };
  if (model.has_jacobian()) {
    sys.jacobian = [&model, modes_at](double t, ConstVectorRef y, SparseMatrix& J) {
      model.jacobian(t, y, modes_at(y), J);
    };
  }
  // IMEX: the contact forces are what makes the system stiff, so they are the implicit part:
  // f_implicit = f(modes) - f(all free), with the Jacobian likewise; the explicit part is the free
  // flight f(all free), one evaluation where f - f_implicit took three.
  auto free = std::make_shared<const ContactModes>(model.all_modes(ContactMode::Free));
  sys.explicit_rhs = [&model, free](double t, ConstVectorRef y, VectorRef yd) { model.rhs(t, y, *free, yd); };
  auto buffer = std::make_shared<Vector>(sys.size);
  sys.implicit_rhs = [&model, modes_at, free, buffer](double t, ConstVectorRef y, VectorRef yd) {
    model.rhs(t, y, modes_at(y), yd);
    model.rhs(t, y, *free, *buffer);
    yd -= *buffer;
  };
  if (model.has_jacobian()) {
    sys.implicit_jacobian = [&model, modes_at, free](double t, ConstVectorRef y, SparseMatrix& J) {
      SparseMatrix J_free;
      model.jacobian(t, y, modes_at(y), J);
      model.jacobian(t, y, *free, J_free);
      J -= J_free;
    };
  }
  return sys;
}

OdeSystem with_ledger(OdeSystem base, std::function<double(ConstVectorRef y)> power) {
  const auto n = static_cast<Eigen::Index>(base.size);
  OdeSystem sys = base;
  sys.size = base.size + 1;
  if (base.positions.size() > 0) {
    sys.positions.resize(n + 1);
    sys.positions << base.positions, false;
  }
  sys.quadratures = Mask::Constant(n + 1, false);
  if (base.quadratures.size() > 0) sys.quadratures.head(n) = base.quadratures;
  sys.quadratures[n] = true;
  sys.rhs = [base, power, n](double t, ConstVectorRef y, VectorRef yd) {
    base.rhs(t, y.head(n), yd.head(n));
    yd[n] = power(y.head(n));
  };
  // Every Jacobian gets the extra row and column with only its (zero) diagonal entry.
  auto extend = [n](const OdeSystem::Jacobian& jac) -> OdeSystem::Jacobian {
    if (!jac) return {};
    return [jac, n](double t, ConstVectorRef y, SparseMatrix& J) {
      jac(t, y.head(n), J);
      // Appended to the compressed columns: insert() uncompressed and recompressed the whole
      // matrix at every call (a third of a GMRES run, which evaluates it every Newton iteration).
      J.makeCompressed();
      const auto nnz = static_cast<Eigen::Index>(J.nonZeros());
      J.conservativeResize(n + 1, n + 1);
      J.resizeNonZeros(nnz + 1);
      J.innerIndexPtr()[nnz] = static_cast<int>(n);
      J.valuePtr()[nnz] = 0.0;
      J.outerIndexPtr()[n + 1] = static_cast<int>(nnz + 1);
    };
  };
  sys.jacobian = extend(base.jacobian);
  if (base.implicit_rhs) {
    sys.implicit_rhs = [base, n](double t, ConstVectorRef y, VectorRef yd) {
      base.implicit_rhs(t, y.head(n), yd.head(n));
      yd[n] = 0.0;
    };
    sys.implicit_jacobian = extend(base.implicit_jacobian);
  }
  if (base.explicit_rhs) {  // the ledger's power is explicit: its implicit part is zero
    sys.explicit_rhs = [base, power, n](double t, ConstVectorRef y, VectorRef yd) {
      base.explicit_rhs(t, y.head(n), yd.head(n));
      yd[n] = power(y.head(n));
    };
  }
  if (base.roots) {
    sys.roots = [base, n](double t, ConstVectorRef y, VectorRef g) { base.roots(t, y.head(n), g); };
  }
  return sys;
}

}  // namespace contact
