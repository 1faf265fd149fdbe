#pragma once
// The SciPy peer (python/scipy_peer.py) run from an experiment: the penalty ball drop under
// scipy.integrate.solve_ivp (BDF, Radau, LSODA, RK45), restarted at every contact switch, run by
// Debian's /usr/bin/python3 and read back as numbers. SciPy is a peer, not a dependency of the
// library: when the interpreter or SciPy is missing, ScipyPeerMissing says what to install.
#include "problems.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace contact {

struct ScipyRun {
  std::string method;  // BDF, Radau, LSODA, RK45
  double rtol, atol;
  double y, v;                         // the final state [m], [m/s]
  std::vector<double> apexes;          // heights of the apexes [m]
  long nfev, njev;                     // right-hand sides and Jacobians
  double cpu_s, cpu_min_s, cpu_max_s;  // per solve: median, min, max over the repeats
  int repeats;                         // solves timed
};

struct ScipyDrop {
  double m = 1, g = 9.81, k = 1e4, c = 0, h0 = 1, v0 = 0, t_end = 1.5;
  std::vector<double> rtols{1e-6};
  double atol_ratio = 1e-2;  // atol = rtol * atol_ratio
  int repeats = 1;
  double budget_s = 0;  // > 0: at least 3 (at most `repeats`) solves, stopping once they took this long
  std::vector<std::string> methods{"BDF", "Radau", "LSODA", "RK45"};
};

// The peer cannot run: the interpreter or SciPy is missing; what() says what to install.
struct ScipyPeerMissing : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// Runs the peer; throws ScipyPeerMissing when it cannot run (found by running it: a separate
// check would start the interpreter and import SciPy once more), and std::runtime_error with its
// output when it fails.
std::vector<ScipyRun> run_scipy_peer(const ScipyDrop& drop);

// The peer on the work-precision ball (problems.hpp: Hooke spring k, to the problem's t_end) at
// each rtol (atol = rtol / 100), each run scored by the problem's own errors of its final state,
// its CPU time the median of 3 to `repeats` solves, as many as fit in `budget_s` (0: all `repeats`).
struct ScoredScipyRun {
  ScipyRun run;
  double error;           // against the spring model (the problem's closed form)
  double error_physical;  // against the rigid ball (the physical reference)
};
std::vector<ScoredScipyRun> scipy_on_ball(const Problem& ball, double k, const std::vector<double>& rtols,
                                          int repeats = 1, double budget_s = 0);

}  // namespace contact
