#include "normal_kept.hpp"

#include "contact_ode/integrators/status.hpp"

#include <fmt/format.h>

#include <limits>

namespace contact {

void require_normal_kept(const ContactGeometry& geo, std::size_t i, double t, ConstVectorRef y, double reach,
                         double dt) {
  const double extent = geo.overlap_extent(i);
  if (!(extent < std::numeric_limits<double>::infinity())) return;  // no normal to turn: no gap to compute
  const double overlap = -geo.gap(i, y);
  // A step that carries the bodies a tenth of the extent or more cannot tell a soft spring from
  // a long step: explicit Euler beyond its stability on the default cradle sent the balls 0.17 m
  // a step (E from 0.085 to 3.4e4 J, which the energy columns show), not a spring too soft.
  if (!(overlap > 0) || reach >= 0.1 * extent || overlap + reach < (1 - 1e-3) * extent) return;
  throw SolverFailure(
      Status::Unresolved, t,
      fmt::format("contact {}'s bodies passed through each other: they overlapped by {:.3g} m{} against "
                  "the {:.3g} m at which the contact's normal turns about (the centres cross); the spring is "
                  "too soft to stop them within their size: raise k{}",
                  i, overlap,
                  reach > 0 ? fmt::format(" ({:.3g} m more within a step at their rate)", reach) : "", extent,
                  dt > 0 ? fmt::format(" (dt = {:g} s resolves their approach)", dt) : ""));
}

}  // namespace contact
