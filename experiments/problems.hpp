#pragma once
// The test problems of the convergence and work-precision studies: a scene, the time its error is
// measured at, the duration of one contact (which sets the fixed steps), and the error of a run's
// final state, scaled to 1 for an error the size of the motion, against either the spring
// solution (penalty methods) or the rigid limit (impulses).
#include "contact_ode/integrators/run_result.hpp"
#include "contact_ode/models/mechanical_system.hpp"

#include <functional>
#include <memory>
#include <string>

namespace contact {

struct Problem {
  std::string name;
  std::shared_ptr<const MechanicalSystem> model;
  double t_end;             // the error is measured at this time [s]
  double contact_duration;  // of one contact [s]
  std::function<double(const RunResult& r, bool rigid)> error;
};

// 1 kg dropped from 1 m onto a Hooke spring k, to t_end. References in closed form (hooke_ball_state,
// rigid_ball_state with e = 1); error max(|x - x*| / h0, |v - v*| / V), V the impact speed.
Problem ball_problem(double k, double t_end);

// A row of `balls` steel balls (ball_chain.hpp) on Hooke springs k, the striker at 1 m/s, measured
// once the pulse has had three pair contacts per ball to cross it. Spring reference: CVODE BDF at
// rtol 1e-12 with the switches located (computed here; a failure throws); rigid reference: the
// last ball leaves at v0 and the others rest. Error: the largest velocity error over v0.
Problem chain_problem(long balls, double k);

}  // namespace contact
