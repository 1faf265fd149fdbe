#include "cvode_driver.hpp"

#include <algorithm>
#include <cmath>

namespace contact {

RunResult drive_cvode(OdeSystem system, ConstVectorRef y0, const CvodeOptions& options,
                      RunRecorder& rec, const CvodeDrive& drive) {
  CvodeSolver solver(std::move(system), 0.0, y0, options);
  if (!drive.root_directions.empty()) solver.set_root_directions(drive.root_directions);
  long events = 0;
  auto stats = [&] {
    SolverStats s = solver.stats();
    s.events += events;
    return s;
  };
  double t = 0.0;
  try {
    for (double t_out = rec.next_sample_time(); std::isfinite(t_out); t_out = rec.next_sample_time()) {
      if (t_out > t) {
        const auto out = solver.advance(t_out);
        t = out.t;
        if (out.root) {
          Vector y = solver.y();
          events += std::count_if(out.roots_found.begin(), out.roots_found.end(), [](int r) { return r != 0; });
          if (drive.on_roots(t, y, out.roots_found)) solver.reinit(t, y);
          continue;
        }
      }
      if (drive.before_sample) drive.before_sample(solver.y());
      rec.sample(t, solver.y());
    }
  } catch (const SolverFailure& f) {
    return rec.fail(f, stats());
  }
  return rec.finish(stats(), t);
}

}  // namespace contact
