// Contact laws: the restitution <-> damping-ratio relation and the laws' values.
#include "contact_law.hpp"
#include "references.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace contact;

// zeta(e) = -ln e / sqrt(pi^2 + ln^2 e) inverts e(zeta) = exp(-zeta pi / sqrt(1 - zeta^2)); both
// are a few elementary operations, so the round trip holds to ~10 ulps.
TEST(ContactLaw, DampingRatioInvertsTheRestitutionOfTheLinearDashpot) {
  for (double e : {1e-6, 0.01, 0.1, 0.3, 0.5, 0.8, 0.95, 0.999999}) {
    const double zeta = damping_ratio_for_restitution(e);
    EXPECT_GT(zeta, 0.0);
    EXPECT_LT(zeta, 1.0);
    EXPECT_NEAR(std::exp(-zeta * std::numbers::pi / std::sqrt(1 - zeta * zeta)), e, 1e-14 + 1e-14 * e);
  }
  EXPECT_EQ(damping_ratio_for_restitution(1.0), 0.0);  // undamped
  EXPECT_EQ(damping_ratio_for_restitution(0.0), 1.0);  // critical: the overlap never reopens
}

TEST(ContactLaw, KelvinVoigtDampingIsTwoZetaSqrtKm) {
  const auto kv = kelvin_voigt_for_restitution(4e6, 0.25, 0.5, false);
  EXPECT_DOUBLE_EQ(kv.c, 2 * damping_ratio_for_restitution(0.5) * std::sqrt(4e6 * 0.25));
  EXPECT_EQ(kv.k, 4e6);
}

TEST(ContactLaw, ForcesDerivativesAndSwitchingFunctions) {
  const ContactLaw hooke = Hooke{1e3};
  EXPECT_EQ(force(hooke, 0.01, -5.0), 10.0);
  EXPECT_EQ(dforce_ddelta(hooke, 0.01, 0.0), 1e3);
  EXPECT_EQ(dforce_drate(hooke, 0.01, 0.0), 0.0);
  EXPECT_EQ(switching(hooke, -0.01, 3.0), -0.01);
  EXPECT_DOUBLE_EQ(stored_energy(hooke, 0.02), 0.2);
  EXPECT_EQ(stored_energy(hooke, -0.02), 0.0);

  const ContactLaw clamped = KelvinVoigt{1e3, 10.0, true};
  // Overlapping but pulling (k d + c dd = 10 - 20 < 0): off, measured as a length.
  EXPECT_DOUBLE_EQ(switching(clamped, 0.01, -2.0), 0.01 - 0.02);
  EXPECT_DOUBLE_EQ(switching(clamped, 0.01, 2.0), 0.01);  // pushing: on, limited by the overlap
  const ContactLaw unclamped = KelvinVoigt{1e3, 10.0, false};
  EXPECT_DOUBLE_EQ(switching(unclamped, 0.01, -2.0), 0.01);  // on while overlapping, even pulling
  EXPECT_DOUBLE_EQ(force(unclamped, 0.01, -2.0), -10.0);
}

// The clamped restitution's closed form exceeds the unclamped target for every zeta in (0, 1)
// and meets it at the undamped end.
TEST(ContactLaw, ClampedRestitutionFormulaLiesAboveTheTarget) {
  for (double e : {0.05, 0.2, 0.5, 0.8, 0.99}) {
    const double zeta = damping_ratio_for_restitution(e);
    EXPECT_GT(clamped_kelvin_voigt_restitution(zeta), e);
    EXPECT_LT(clamped_kelvin_voigt_restitution(zeta), 1.0);
  }
  EXPECT_DOUBLE_EQ(clamped_kelvin_voigt_restitution(0.0), 1.0);
}
