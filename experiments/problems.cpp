#include "problems.hpp"

#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/models/ball_chain.hpp"
#include "contact_ode/models/ball_drop.hpp"
#include "experiment.hpp"

#include <cmath>

namespace contact {

Problem ball_problem(double k, double t_end) {
  const double m = 1.0, g = 9.81, h0 = 1.0, V = std::sqrt(2 * g * h0);
  auto error = [=](const RunResult& r, bool rigid) {
    const Vector& y = r.samples.back().y;
    const BallState ref =
        rigid ? rigid_ball_state(h0, 0.0, g, 1.0, t_end) : hooke_ball_state(m, k, h0, 0.0, g, t_end);
    return std::max(std::abs(y[0] - ref.x) / h0, std::abs(y[1] - ref.v) / V);
  };
  return {"ball", std::make_shared<BallDrop>(BallDropParams{m, g, h0, 0.0, 1.0, Hooke{k}}), t_end,
          hooke_contact(m, k, V, g).duration, error};
}

Problem chain_problem(long balls, double k) {
  const BallChainParams p{.n = static_cast<std::size_t>(balls), .law = Hooke{k}};
  auto chain = std::make_shared<BallChain>(p);
  const double contact = hooke_contact(p.m / 2, k, p.v0, 0.0).duration;
  const double t_end = p.approach / p.v0 + 3.0 * static_cast<double>(p.n) * contact;
  Method reference{.name = "penalty"};
  reference.integrator.rtol = 1e-12;
  reference.integrator.atol = 1e-14;
  reference.integrator.max_steps = 10000000;
  const Vector spring =
      require(solve(*chain, reference, {.t_end = t_end, .sample_dt = t_end}), "chain reference")
          .samples.back()
          .y;
  auto error = [=](const RunResult& r, bool rigid) {
    const Vector& y = r.samples.back().y;
    double err = 0;
    for (std::size_t b = 0; b < p.n; ++b) {
      const auto i = static_cast<Eigen::Index>(2 * b + 1);
      const double ref = rigid ? (b + 1 == p.n ? p.v0 : 0.0) : spring[i];
      err = std::max(err, std::abs(y[i] - ref) / p.v0);
    }
    return err;
  };
  return {"chain", chain, t_end, contact, error};
}

}  // namespace contact
