// The memory a run is refused for (memory_estimate) bounds what it holds: each run here is measured
// as the growth of this process's peak resident memory (VmHWM, reset through /proc/self/clear_refs
// before the run) on scenes of 1e5 and 2e5 state entries, where the methods' fixed costs are small.
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/scene_registry.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

using namespace contact;

namespace {

// A field of /proc/self/status [bytes] (its "VmRSS:" or "VmHWM:" line, in kB).
double status_bytes(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string key;
  double kb = -1;
  while (status >> key)
    if (key == field && status >> kb) return 1024 * kb;
  return -1;
}

// The peak resident memory a call adds to what the process holds when it starts [bytes], or -1
// where /proc cannot reset the peak.
template <typename F>
double peak_growth(F&& run) {
  if (!(std::ofstream("/proc/self/clear_refs") << "5")) return -1;
  const double before = status_bytes("VmRSS:");
  run();
  return status_bytes("VmHWM:") - before;
}

struct Case {
  std::string scene, method;
  Method settings;
  double balls = 1e5;
};

}  // namespace

// 16 working doubles per entry were taken as every ODE integrator's lower bound; a 1e7-ball chain
// under penalty held 8 GB where that said 2.6, so runs past the limit started (and, under a ulimit,
// SUNDIALS dereferenced the NULL of an allocation that failed). The measured growths are 11 to 16
// doubles per entry for the fixed-step loops, 24 to 122 for the integrators and the implicit step,
// and hundreds for the engines' worlds (ODE's growing with the chain, 21 GB at 4e5 balls).
TEST(RunMemory, TheEstimateBoundsWhatARunHolds) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's shadow memory and quarantine are not the run's own";
#endif
  const std::vector<Case> cases = {
      {"ball-chain", "penalty", {}},
      {"ball-chain", "penalty", {.integrator = {.linear_solver = LinearSolverKind::Klu}}},
      {"ball-chain", "penalty", {.integrator = {.method = "arkode-imex"}}},
      {"ball-chain", "event-ode", {}},
      {"ball-chain", "game-implicit-spring", {.dt = 1e-6}},
      {"ball-chain", "game-euler", {.dt = 1e-6}},
      {"ball-chain", "sequential-impulses", {.dt = 1e-6}},
      {"ball-stack", "penalty", {}},
      {"ball-chain", "bullet", {}, 5e4},
      {"ball-chain", "ode", {}, 5e4},  // 523 doubles per entry, and growing with the chain
  };
  for (const Case& c : cases) {
    const auto scene = make_scene(c.scene, {{"n", c.balls}}, "");
    Method method = c.settings;
    method.name = c.method;
    const SolveOptions span{.t_end = 1e-5, .sample_dt = 1e-5};
    const double estimate = memory_estimate(*scene, method, span);
    RunResult r;
    const double growth = peak_growth([&] { r = solve(*scene, method, span); });
    if (growth < 0) GTEST_SKIP() << "/proc/self/clear_refs cannot reset the peak here";
    EXPECT_TRUE(r.ok()) << c.scene << " " << c.method << ": " << r.message;
    EXPECT_LE(growth, estimate) << c.scene << " " << c.method << " " << method.integrator.method << ": "
                                << growth / 8 / static_cast<double>(scene->state_size())
                                << " doubles per entry";
  }
}
