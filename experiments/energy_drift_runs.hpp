#pragma once
// energy_drift's runs: the undamped ball drop (e = 1, Hooke k for the penalty methods, m = 1 kg,
// h0 = 1 m) over `bounces` rigid bounces under every method at each step or tolerance, and each
// rigid scene under the rigid methods. Refused before any starts where one could only end in a
// work limit, naming what fits.
#include "contact_ode/integrators/method_registry.hpp"

#include <memory>
#include <string>
#include <vector>

namespace contact {

struct DriftSettings {
  double k = 1e5;
  long bounces = 100;
  std::vector<double> dts{1e-3, 1e-4}, rtols{1e-4, 1e-6, 1e-8}, rigid_dts{1e-4, 1e-5},
      rigid_rtols{1e-6, 1e-8};
  std::string scenes = "all";
};

// One run: (system, method, setting name, setting value), the scene, the method and its span.
struct DriftRun {
  std::string system, method, setting;
  double value;
  std::shared_ptr<const Dynamics> scene;
  Method settings;
  SolveOptions span;
};

// Throws std::invalid_argument naming --bounces or --rigid-dts where a run could not fit its work
// bound (the ball's sequential impulses at --bounces 10000 were refused after 42 s of the others).
std::vector<DriftRun> drift_runs(const DriftSettings& s);

}  // namespace contact
