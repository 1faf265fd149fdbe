#pragma once
// A spring too soft for its bodies lets them overlap until their centres cross: two balls' normal
// then turns about, and the spring pushes the cue ball on through the red one. Shared by the
// penalty ODE (at each contact's located deepest point) and the spring time-steppers (at each
// step's end, where the crossing may fall inside the step).
#include "contact_ode/models/mechanical_system.hpp"

#include <cstddef>

namespace contact {

// Throws SolverFailure (Status::Unresolved) when contact i's overlap at y, plus `reach` (how far
// a step carries the bodies towards each other at their gap rate; 0 at a located deepest point),
// is within 1e-3 of ContactGeometry::overlap_extent(i), where the normal turns about, and the step
// resolves their approach (reach below a tenth of the extent). `dt`: the fixed step (0 for none),
// named in the message.
void require_normal_kept(const ContactGeometry& geo, std::size_t i, double t, ConstVectorRef y, double reach,
                         double dt);

}  // namespace contact
