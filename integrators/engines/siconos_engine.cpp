// Siconos 4.4 on the spheres-on-a-line scenes (siconos_line.hpp): event-driven impacts with
// Newton's law, LSODAR between them at rtol 1e-10, atol 1e-12, the run sampled every dt. The
// engine's answer to "which contact method": no step error at the impacts at all, only the
// integrator's and the event location's tolerance.
#include "engine_world.hpp"
#include "siconos_line.hpp"

#include <memory>
#include <mutex>

namespace contact {

namespace {

// Siconos keeps settings in globals (its event-driven tolerance, written by every simulation):
// one Siconos world at a time in a process, as ODE's (ode_engine.cpp).
std::mutex& siconos_in_use() {
  static std::mutex m;
  return m;
}

class SiconosWorld final : public EngineWorld {
 public:
  explicit SiconosWorld(const EngineScene& s)
      : line_(SiconosSpheres{.radius = s.layout.radius,
                             .vertical = s.layout.vertical,
                             .floor = s.layout.floor,
                             .g = s.layout.g,
                             .mass = s.layout.mass,
                             .centre = s.centre,
                             .velocity = s.velocity,
                             .restitution = s.restitution,
                             .dt = s.dt,
                             .rtol = 1e-10,
                             .atol = 1e-12}) {}

  void step(double h) override {
    try {
      line_.step(
          h, [](double t) { throw_if_stop_requested(t); }, report_);
    } catch (const SolverFailure&) {
      throw;  // a stop request: the run ends interrupted
    } catch (const std::runtime_error& e) {
      throw EngineError(e.what());
    }
  }
  void read(std::vector<double>& centre, std::vector<double>& velocity) const override {
    line_.read(centre, velocity);
  }
  void impulses(std::vector<double>& impulse) const override { line_.impulses(impulse); }
  bool report_impacts(ImpactReport report) override {
    report_ = std::move(report);
    return true;
  }

 private:
  std::lock_guard<std::mutex> one_world_at_a_time_{siconos_in_use()};  // first: held until line_ is gone
  SiconosLine line_;
  ImpactReport report_;
};

}  // namespace

std::vector<MethodInfo> siconos_methods() {
  MethodInfo info = engine_method(
      "siconos", "Siconos 4.4 event-driven: LSODAR flight, Newton's impact law by LCP, Zeno to rest", false,
      MethodInfo{}.working_doubles,  // the default, besides its dense matrix (below)
      [](const EngineScene& s) -> std::unique_ptr<EngineWorld> {
        try {  // Siconos's refusal of the scene fails the run, as its step failures do
          return std::make_unique<SiconosWorld>(s);
        } catch (const std::runtime_error& e) {
          throw EngineError(e.what());
        }
      });
  // LSODAR's Jacobian is dense over every state: (2 n)^2 numbers for n balls, 3.2 GB at 1e4 and
  // 29 GB at 3e4, which would have gone to the kernel's OOM killer, not to an error.
  info.dense_state_matrices = 1;
  return {info};
}

}  // namespace contact
