#pragma once
// Optional capability: bodies on a line whose forces act between neighbours only, so that a
// process holding bodies [first, first + count) can evaluate their derivatives from its own state
// and one neighbour on each side: what a distributed integrator (integrators/distributed/) needs.
#include "contact_ode/models/linear_algebra.hpp"

#include <cstddef>

namespace contact {

class NeighbourDynamics {
 public:
  virtual ~NeighbourDynamics() = default;
  virtual std::size_t bodies() const = 0;
  virtual std::size_t body_stride() const = 0;  // state entries per body, in body order
  // y' of bodies [first, first + count), each contact's law where its switching function is
  // positive, from `window`: the state of bodies [first - 1, first + count + 1) clipped to
  // [0, bodies()).
  virtual void range_rhs(double t, std::size_t first, std::size_t count, ConstVectorRef window,
                         VectorRef ydot) const = 0;
};

}  // namespace contact
