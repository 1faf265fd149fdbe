#pragma once
// What an adapter to an external physics engine (MuJoCo, Bullet, ODE) implements, and how it
// becomes a method: the engine builds its own world once from the scene's spheres on a line
// (models' SphereLine), steps it at the method's dt, and its bodies' state is read back into the
// scene's state after every step, so that the shared time-stepping loop records contacts, apexes,
// penetration and the energy ledger exactly as for the project's own methods.
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/mechanical_system.hpp"

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace contact {

// The scene as an engine needs it: the spheres, and per contact Newton's restitution, the
// penalty law (when linear) and the effective inverse mass w.
struct EngineScene {
  SphereLineLayout layout;
  std::vector<double> centre, velocity;  // initial, along the axis [m], [m/s]
  std::vector<double> restitution;       // per contact
  std::vector<LinearLaw> law;            // per contact (NaN when the law is not linear)
  std::vector<double> inverse_mass;      // per contact [1/kg]
  double dt;                             // the engine's step [s]
  // The sphere ids of contact c: {-1 (the floor) or a sphere, a sphere}.
  std::pair<int, int> bodies(std::size_t c) const;
  // The contact joining two spheres (or the floor, -1) in either order; -1 when none does.
  int contact_between(int a, int b) const;
};

// An engine's own report that its step failed (its message): the run ends with a typed failure.
class EngineError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class EngineWorld {
 public:
  virtual ~EngineWorld() = default;
  // One step of the engine's own loop, of length h: the scene's dt, or less for a run's last step
  // where dt does not divide the span (the state is reported at the span's end, so the engine must
  // stop there, not a whole dt later). Throws EngineError when the engine reports a failure.
  virtual void step(double h) = 0;
  // Each sphere's centre along the axis and its velocity [m], [m/s].
  virtual void read(std::vector<double>& centre, std::vector<double>& velocity) const = 0;
  // The normal impulse each contact applied during the last step [N s], >= 0.
  virtual void impulses(std::vector<double>& impulse) const = 0;
  // An engine that resolves each impact at its instant (event-driven) hands `report` every impact of
  // its later steps, with the spheres' centres and velocities just before it and each contact's
  // impulse in it, and returns true: the impact's loss is booked from the impact itself. A
  // time-stepping engine, whose step's impulses are its impacts, returns false.
  using ImpactReport =
      std::function<void(const std::vector<double>& centre, const std::vector<double>& velocity,
                         const std::vector<double>& impulse)>;
  virtual bool report_impacts(ImpactReport /*report*/) { return false; }
};

using EngineFactory = std::function<std::unique_ptr<EngineWorld>(const EngineScene&)>;

// A method that runs an engine. `springs`: the setting models the scene's penalty law (its
// dashpot's work is booked, its spring's energy counted); otherwise the engine is asked for
// Newton's law with the scene's restitution, whose loss is booked once per impact.
// `working_doubles`: the engine's memory per state entry, as MethodInfo's (an engine's world holds
// far more per body than our state: 3D bodies, contacts, its solver's rows).
MethodInfo engine_method(std::string name, std::string description, bool springs, double working_doubles,
                         EngineFactory make);

// Engines available in this build, in registry order (each optional at configure time).
std::vector<MethodInfo> mujoco_methods();
std::vector<MethodInfo> bullet_methods();
std::vector<MethodInfo> ode_engine_methods();
std::vector<MethodInfo> siconos_methods();

}  // namespace contact
