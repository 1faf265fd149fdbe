#include "contact_ode/analysis/rigid_observables.hpp"

#include <cmath>

namespace contact::rigid {

// The numbers a reader checks for each scene, read off the end of a run.
Observables observe(const std::string& scene, const RigidScene& s, const RunResult& r) {
  const auto bodies = s.bodies_at(r.samples.back().y);
  // The first apex of a ball's contact with the floor (the scene's last body), over the gap it was
  // released from: the bounce's e^2.
  auto first_apex = [&](std::size_t body) {
    const std::pair<std::size_t, std::size_t> with_floor{body, bodies.size() - 1};
    const Vector y0 = s.initial_state();
    for (std::size_t i = 0; i < s.contact_count(); ++i) {
      if (s.pair(i) != with_floor) continue;
      const double released = s.gap(i, y0);
      for (const auto& a : r.apexes)
        if (a.contact == i) return a.gap / released;
    }
    return std::nan("");
  };
  if (scene == "snooker") {
    // With projection alone the first contact never closes: it pushes from its start to the end.
    const double pushing = r.contacts.empty()            ? 0.0
                           : r.contacts.front().closed() ? r.contacts.front().duration()
                                                         : r.t_reached - r.contacts.front().t_begin;
    return {{"cue_vx_mps", bodies[0].velocity.x()},
            {"red_vx_mps", bodies[1].velocity.x()},
            {"red_displacement_m", bodies[1].position.x() - s.bodies()[1].position.x()},
            {"contact_duration_s", pushing}};
  }
  if (scene == "planet")
    return {{"cue_vx_mps", bodies[0].velocity.x()}, {"planet_speed_mps", bodies[1].velocity.norm()}};
  if (scene == "spinning-box")
    return {{"ball_speed_mps", bodies[1].velocity.norm()},
            {"box_spin_radps", bodies[0].angular_velocity.norm()}};
  if (scene == "off-centre")
    return {{"box_spin_radps", bodies[1].angular_velocity.norm()},
            {"box_speed_mps", bodies[1].velocity.norm()}};
  if (scene == "rubber-steel")
    return {{"rubber_apex_ratio", first_apex(0)}, {"steel_apex_ratio", first_apex(1)}};
  if (scene == "cradle")
    return {{"striker_vx_mps", bodies[0].velocity.x()}, {"last_vx_mps", bodies[4].velocity.x()}};
  if (scene == "wedge")  // symmetric physics would give the two balls equal speeds
    return {{"upper_speed_mps", bodies[1].velocity.norm()},
            {"lower_speed_mps", bodies[2].velocity.norm()},
            {"striker_vy_mps", bodies[0].velocity.y()}};
  return {};
}

}  // namespace contact::rigid
