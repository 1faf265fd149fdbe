#pragma once
// Siconos 4.4 (libsiconos-kernel-dev) behind a plain interface: its headers need C++17 (Boost
// uBLAS fails under C++20), so they are compiled alone, in siconos_line.cpp at C++17, and this
// header uses nothing newer (siconos_engine.cpp, C++20, adapts it to an EngineWorld).
//
// Spheres on a line as Lagrangian linear time-invariant systems (one degree of freedom each,
// the centre along the axis), each contact a Lagrangian linear relation (the gap) with Newton's
// impact law, simulated event-driven: LSODAR integrates the smooth motion and locates the
// contacts, an LCP at velocity level applies Newton's law at each impact, an LCP at acceleration
// level holds contacts that rest. Siconos's own treatment of accumulations (Zeno) brings a
// bouncing ball to rest.
#include <functional>
#include <memory>
#include <vector>

namespace contact {

struct SiconosSpheres {
  double radius;
  bool vertical, floor;
  double g;                                    // along -axis when vertical [m/s^2]
  std::vector<double> mass, centre, velocity;  // per sphere
  std::vector<double> restitution;             // per contact (floor first, then neighbours)
  double dt;                                   // the output step: a step() advances by it or less [s]
  double rtol, atol;                           // LSODAR's tolerances
};

class SiconosLine {
 public:
  explicit SiconosLine(const SiconosSpheres& spheres);
  ~SiconosLine();
  SiconosLine(const SiconosLine&) = delete;
  SiconosLine& operator=(const SiconosLine&) = delete;

  // Processes every event up to the next output time, h later (dt, or less for a run's last
  // step); throws std::runtime_error with Siconos's message when it fails, or when more than a
  // million events fall in one step (judged after 1e4 of them by the time they covered).
  // `checkpoint` is called with the time reached every 1000 events; what it throws ends the step.
  // `at_impact` is called at each impact with the centres and velocities just before it and each
  // contact's impulse in it [m], [m/s], [N s].
  using ImpactObserver =
      std::function<void(const std::vector<double>& centre, const std::vector<double>& velocity,
                         const std::vector<double>& impulse)>;
  void step(double h, const std::function<void(double t)>& checkpoint = {},
            const ImpactObserver& at_impact = {});
  void read(std::vector<double>& centre, std::vector<double>& velocity) const;
  // Per contact over the last step: the impulses of its impacts plus its resting force times the
  // time it held [N s].
  void impulses(std::vector<double>& impulse) const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace contact
