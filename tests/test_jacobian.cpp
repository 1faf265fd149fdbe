// Analytic Jacobians against central differences, with each column's tolerance derived:
// central differences err by truncation h^2 |d^3 f / dy_j^3| / 6 plus rounding, at most
// 2 eps max|f| / h for the two evaluations, doubled for the analytic side and the subtraction.
// The penalty right-hand sides are affine in each state entry within one contact mode (Hooke,
// Kelvin–Voigt, and Hunt–Crossley with n = 1, which is bilinear: each column moves one entry), so
// only rounding remains; the Hertz force K delta^{3/2} (1 + chi delta_dot) / m has
// |d^3/d delta^3| = (3/8) K delta^{-3/2} |1 + chi delta_dot| / m in the position column.
#include "contact_ode/models/ball_drop.hpp"
#include "contact_ode/models/ball_stack.hpp"
#include "contact_ode/models/spring_mass.hpp"
#include "unit_roundoff.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <variant>

using namespace contact;

namespace {

double step(ConstVectorRef y, Eigen::Index j) { return 1e-6 * std::max(1.0, std::abs(y[j])); }

Matrix central_difference(const Dynamics& s, ConstVectorRef y, const ContactModes& modes, double& f_max) {
  const auto n = y.size();
  Matrix J(n, n);
  Vector yp = y, ym = y, fp(n), fm(n);
  f_max = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double h = step(y, j);
    yp[j] = y[j] + h;
    ym[j] = y[j] - h;
    s.rhs(0.0, yp, modes, fp);
    s.rhs(0.0, ym, modes, fm);
    J.col(j) = (fp - fm) / (2 * h);
    f_max = std::max({f_max, fp.cwiseAbs().maxCoeff(), fm.cwiseAbs().maxCoeff()});
    yp[j] = ym[j] = y[j];
  }
  return J;
}

// third[j]: a bound on |d^3 f / dy_j^3| at y (0 where f is affine in y_j).
void expect_jacobian_matches(const Dynamics& s, ConstVectorRef y, const ContactModes& modes,
                             const std::vector<double>& third) {
  SparseMatrix sparse;
  s.jacobian(0.0, y, modes, sparse);
  const Matrix analytic(sparse);
  // The pattern holds the whole diagonal (mechanical_system.hpp says why).
  for (Eigen::Index d = 0; d < sparse.rows(); ++d) {
    bool stored = false;
    for (SparseMatrix::InnerIterator it(sparse, d); it; ++it) stored = stored || it.row() == d;
    EXPECT_TRUE(stored) << s.name() << ": diagonal entry " << d << " missing from the pattern";
  }
  double f_max = 0;
  const Matrix numeric = central_difference(s, y, modes, f_max);
  for (Eigen::Index j = 0; j < y.size(); ++j) {
    const double h = step(y, j);
    const double tol = 4 * kEps * f_max / h + h * h / 6 * third[static_cast<std::size_t>(j)];
    EXPECT_LE((analytic.col(j) - numeric.col(j)).cwiseAbs().maxCoeff(), tol)
        << s.name() << " column " << j << "\n"
        << analytic << "\n"
        << numeric;
  }
}

}  // namespace

TEST(Jacobian, BallDropMatchesCentralDifferencesForEveryLawAndMode) {
  const double m = 2.0;
  const std::vector<ContactLaw> laws = {Hooke{1e6}, kelvin_voigt_for_restitution(1e6, m, 0.6, false),
                                        kelvin_voigt_for_restitution(1e6, m, 0.6, true),
                                        HuntCrossley{1e8, 1.5, 0.3}, HuntCrossley{1e6, 1.0, 0.3}};
  for (const auto& law : laws) {
    const BallDrop ball({m, 9.81, 1.0, 0.0, 0.6, law});
    for (const Vector& y : {Vector{{-1e-3, -2.0}}, Vector{{-2e-4, 1.5}}, Vector{{0.3, -1.0}}})
      for (auto mode : {ContactMode::Free, ContactMode::Penalty, ContactMode::Resting}) {
        double third_x = 0;
        if (const auto* hc = std::get_if<HuntCrossley>(&law); hc && mode == ContactMode::Penalty) {
          // The bound must hold over the stencil [delta - h, delta + h]: delta^{-3/2} is largest at
          // delta - h (the bound is attained to 1e-5 at delta = 2e-4 m, h = 1e-6).
          const double delta = std::abs(y[0]) - 1e-6, rate = -y[1];
          third_x = std::abs(hc->n * (hc->n - 1) * (hc->n - 2)) * hc->k * std::pow(delta, hc->n - 3) *
                    std::abs(1 + hc->chi * rate) / m;
        }
        expect_jacobian_matches(ball, y, {mode}, {third_x, 0.0});
      }
  }
}

TEST(Jacobian, SpringMassMatchesCentralDifferences) {
  const SpringMass spring(0.5, 2e3, 0.1, -0.2);
  expect_jacobian_matches(spring, spring.initial_state(), {}, {0.0, 0.0});
}

// The stack couples each ball to the contacts below and above it; Kelvin–Voigt is affine in every
// entry within a mode, so only rounding remains. Mixed modes, overlapping and open contacts.
TEST(Jacobian, BallStackMatchesCentralDifferencesInMixedModes) {
  const BallStack stack({.n = 3, .m = 0.2, .law = KelvinVoigt{1e5, 30.0, false}});
  // Contacts: overlap, overlap, open. Overlaps of 1e-5 m keep the rounding of y +- h (eps |y| / h
  // times k / m) below the rounding the tolerance allows for.
  const Vector y{{-1e-5, -0.3, -3e-5, 0.2, 1e-4, -0.1}};
  using M = ContactMode;
  for (const ContactModes& modes :
       {ContactModes{M::Penalty, M::Penalty, M::Penalty}, ContactModes{M::Penalty, M::Free, M::Penalty},
        ContactModes{M::Resting, M::Penalty, M::Free}})
    expect_jacobian_matches(stack, y, modes, std::vector<double>(6, 0.0));
}
