// Analytic Jacobians against central differences.
// Central difference error: truncation h^2 |f'''| / 6 plus rounding eps |f| / h. The penalty
// right-hand sides are affine in the state within one contact mode (Hooke, Kelvin–Voigt), so the
// truncation term vanishes and only rounding remains: with h = 1e-6 (scaled) and |f| ~ k delta / m,
// the error is ~ 1e-10 relative to the largest entry. The Hunt-Crossley force K delta^{3/2} is not
// affine: its truncation term, h^2 K delta^{-3/2} / 16 relative to the entry 1.5 K delta^{1/2},
// is ~1e-5 at delta = 2e-4 m with h = 1e-6. We allow 2e-5 of the largest entry.
#include "ball_drop.hpp"
#include "spring_mass.hpp"

#include <gtest/gtest.h>

using namespace contact;

namespace {

Matrix central_difference(const MechanicalSystem& s, ConstVectorRef y, const ContactModes& modes) {
  const auto n = y.size();
  Matrix J(n, n);
  Vector yp = y, ym = y, fp(n), fm(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const double h = 1e-6 * std::max(1.0, std::abs(y[j]));
    yp[j] = y[j] + h;
    ym[j] = y[j] - h;
    s.rhs(0.0, yp, modes, fp);
    s.rhs(0.0, ym, modes, fm);
    J.col(j) = (fp - fm) / (2 * h);
    yp[j] = ym[j] = y[j];
  }
  return J;
}

void expect_jacobian_matches(const MechanicalSystem& s, ConstVectorRef y, const ContactModes& modes) {
  SparseMatrix sparse;
  s.jacobian(0.0, y, modes, sparse);
  const Matrix analytic(sparse);
  // The pattern holds the whole diagonal (mechanical_system.hpp says why).
  for (Eigen::Index d = 0; d < sparse.rows(); ++d) {
    bool stored = false;
    for (SparseMatrix::InnerIterator it(sparse, d); it; ++it) stored = stored || it.row() == d;
    EXPECT_TRUE(stored) << s.name() << ": diagonal entry " << d << " missing from the pattern";
  }
  const Matrix numeric = central_difference(s, y, modes);
  const double scale = std::max(1.0, numeric.cwiseAbs().maxCoeff());
  EXPECT_LE((analytic - numeric).cwiseAbs().maxCoeff(), 2e-5 * scale) << s.name() << "\\n" << analytic << "\\n" << numeric;
}

}  // namespace

TEST(Jacobian, BallDropMatchesCentralDifferencesForEveryLawAndMode) {
  const std::vector<ContactLaw> laws = {Hooke{1e6}, kelvin_voigt_for_restitution(1e6, 2.0, 0.6, false),
                                        kelvin_voigt_for_restitution(1e6, 2.0, 0.6, true),
                                        HuntCrossley{1e8, 1.5, 0.3}, HuntCrossley{1e6, 1.0, 0.3}};
  for (const auto& law : laws) {
    const BallDrop ball({2.0, 9.81, 1.0, 0.0, 0.6, law});
    for (const Vector& y : {Vector{{-1e-3, -2.0}}, Vector{{-2e-4, 1.5}}, Vector{{0.3, -1.0}}})
      for (auto mode : {ContactMode::Free, ContactMode::Penalty, ContactMode::Resting})
        expect_jacobian_matches(ball, y, {mode});
  }
}

TEST(Jacobian, SpringMassMatchesCentralDifferences) {
  const SpringMass spring(0.5, 2e3, 0.1, -0.2);
  expect_jacobian_matches(spring, spring.initial_state(), {});
}
