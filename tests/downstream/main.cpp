// Drops a ball by name, solves it with the exact event-driven method by name, and checks the
// first apex against Newton's restitution law: h1 = e^2 h0. Exit 0 when it holds.
#include <cmath>
#include <cstdio>
#include <exception>

#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/scene_registry.hpp"

int main() {
  try {
    const double h0 = 2.0, e = 0.8;
    const auto ball = contact::make_scene("ball-drop", {{"h0", h0}, {"e", e}});
    const auto run = contact::solve(*ball, contact::Method{.name = "event-exact"}, {.t_end = 1.5});
    if (!run.ok() || run.apexes.empty()) {
      std::fprintf(stderr, "downstream: no apex (%s)\n", run.message.c_str());
      return 1;
    }
    const double apex = run.apexes.front().gap, expected = e * e * h0;
    std::printf("first apex %.12f m, e^2 h0 = %.12f m\n", apex, expected);
    // event-exact flies in closed form and finds the impact by a root of a quadratic: the apex
    // is exact to rounding.
    return std::fabs(apex - expected) < 1e-9 * h0 ? 0 : 1;
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "downstream: %s\n", ex.what());
    return 1;
  }
}
