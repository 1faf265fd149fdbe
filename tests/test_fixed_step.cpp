// Fixed-step schemes on the free spring x'' = -w^2 x (models/spring_mass.hpp).
//
// Explicit Euler: x+ = x + h v, v+ = v - h w^2 x, so
//   v+^2 + w^2 x+^2 = (1 + h^2 w^2)(v^2 + w^2 x^2):
// the energy grows by exactly (1 + w^2 h^2) every step, whatever h.
//
// Semi-implicit Euler: v+ = v - h w^2 x, x+ = x + h v+. Its step matrix has determinant 1 and
// trace 2 - h^2 w^2, so the eigenvalues satisfy l + 1/l = 2 - (hw)^2. For hw < 2 they lie on the
// unit circle and the scheme conserves the modified energy I = v^2 + w^2 x^2 - h w^2 x v, which is
// positive definite. With E = (v^2 + w^2 x^2)/2, the ratio 2E/I lies in [1/(1 + hw/2), 1/(1 - hw/2)],
// so from any start E_n / E_0 <= (1 + hw/2) / (1 - hw/2), and from x = 0 (where 2E = I) the orbit's
// largest energy is E_0 / (1 - hw/2), approached as the iterates sweep the ellipse I = const.
// For hw > 2 one eigenvalue is real with |l| = ((hw)^2 - 2 + hw sqrt((hw)^2 - 4)) / 2 > 1, and the
// energy grows asymptotically by l^2 per step.
#include "contact_ode/integrators/fixed_step.hpp"
#include "contact_ode/models/spring_mass.hpp"
#include "unit_roundoff.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace contact;

namespace {

const Mask kPositions = Mask{{true, false}};

OdeSystem::Rhs rhs_of(const SpringMass& s) {
  const ContactModes none;
  return [&s, none](double t, ConstVectorRef y, VectorRef yd) { s.rhs(t, y, none, yd); };
}

}  // namespace

TEST(ExplicitEuler, EnergyGrowsByExactlyOnePlusOmegaSquaredDtSquaredPerStep) {
  const SpringMass spring(2.0, 800.0, 0.01, 0.3);  // w = 20 rad/s
  const auto f = rhs_of(spring);
  for (double wh : {0.01, 0.3, 1.0, 3.0}) {
    const double h = wh / spring.omega();
    Vector y = spring.initial_state();
    FixedStepWork work(2);
    for (int n = 0; n < 50; ++n) {
      const double E = spring.energy(y);
      fixed_step(FixedStepScheme::ExplicitEuler, f, kPositions, 0.0, h, y, work);
      // One step rounds each of x, v once and the energy's few products: ~8 ulps relative.
      EXPECT_NEAR(spring.energy(y) / E, 1 + wh * wh, 8 * kEps * (1 + wh * wh))
          << "w h = " << wh << ", step " << n;
    }
  }
}

TEST(SemiImplicitEuler, EnergyStaysWithinTheModifiedEnergyBoundBelowOmegaDtTwo) {
  const SpringMass spring(1.0, 1e4, 0.0, 1.0);  // w = 100 rad/s
  const auto f = rhs_of(spring);
  for (double wh : {0.1, 1.0, 1.9, 1.99}) {
    const double h = wh / spring.omega(), peak = 1 / (1 - wh / 2);
    Vector y = spring.initial_state();  // x = 0
    FixedStepWork work(2);
    const double E0 = spring.energy(y);
    double worst = 0;
    for (int n = 0; n < 100000; ++n) {
      fixed_step(FixedStepScheme::SemiImplicitEuler, f, kPositions, 0.0, h, y, work);
      worst = std::max(worst, spring.energy(y) / E0);
    }
    // Upper side: rounding perturbs the invariant by ~ulps per step; over 1e5 steps a random walk
    // of sqrt(1e5) * few ulps ~ 1e-12 relative. Lower side: 1e5 iterates sweep the ellipse densely,
    // and E is flat (quadratic) near its peak, so an angular gap d costs O(d^2) << 1e-3.
    EXPECT_LE(worst, peak * (1 + 1e-10)) << "w h = " << wh;
    EXPECT_GE(worst, peak * (1 - 1e-3)) << "w h = " << wh;
    EXPECT_LE(peak, (1 + wh / 2) / (1 - wh / 2));  // inside the bound for any start
  }
}

TEST(SemiImplicitEuler, EnergyGrowsByTheUnstableEigenvalueSquaredAboveOmegaDtTwo) {
  const SpringMass spring(1.0, 1e4, 0.0, 1.0);
  const auto f = rhs_of(spring);
  for (double wh : {2.01, 2.1, 3.0}) {
    const double h = wh / spring.omega();
    const double lambda = (wh * wh - 2 + wh * std::sqrt(wh * wh - 4)) / 2;
    Vector y = spring.initial_state();
    FixedStepWork work(2);
    // After the stable mode has decayed (its eigenvalue is 1/lambda), the energy ratio per step
    // tends to lambda^2; 200 steps put the other mode below 1/lambda^400 of it.
    for (int n = 0; n < 200; ++n) {
      fixed_step(FixedStepScheme::SemiImplicitEuler, f, kPositions, 0.0, h, y, work);
      y /= y.norm();  // rescale: the ratio is scale-free and this keeps it finite
    }
    const double E = spring.energy(y);
    fixed_step(FixedStepScheme::SemiImplicitEuler, f, kPositions, 0.0, h, y, work);
    EXPECT_NEAR(spring.energy(y) / E, lambda * lambda, 1e-9 * lambda * lambda) << "w h = " << wh;
    EXPECT_GT(lambda, 1.0);
  }
}
