// The log-log helpers of analysis/fit.hpp that every sweep and convergence table uses.
#include "contact_ode/analysis/fit.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace contact;

// The sweeps' k grids: per_decade points a decade, the decades exactly lo * 10^m (a k of 1e3 was
// 999.99999999999977, so that a CSV reader's k == 1000 found nothing), the points between them
// lo * 10^(m + i / per_decade) to rounding, the ends exact.
TEST(LogGrid, DecadesAreExactPowersOfTenAndTheRestEvenlySpacedInLog) {
  EXPECT_EQ(log_grid(1e2, 1e8, 1), (std::vector<double>{1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8}));
  EXPECT_EQ(log_grid(1e2, 1e10, 1).size(), 9u);
  const auto thirds = log_grid(1e2, 1e10, 3);
  ASSERT_EQ(thirds.size(), 25u);
  for (std::size_t j = 0; j < thirds.size(); ++j) {
    if (j % 3 == 0) {
      EXPECT_EQ(thirds[j], 1e2 * std::pow(10.0, static_cast<double>(j / 3))) << j;
    }
    EXPECT_NEAR(std::log10(thirds[j]), 2 + static_cast<double>(j) / 3, 4e-15) << j;  // 2 ulps of 10
  }
  const auto odd = log_grid(3.7, 3.7e4, 2);  // decades of lo, not of ten
  ASSERT_EQ(odd.size(), 9u);
  EXPECT_EQ(odd[2], 3.7 * 10);
  EXPECT_EQ(odd.back(), 3.7e4);
  EXPECT_EQ(log_grid(5.0, 5.0, 3), std::vector<double>{5.0});
  EXPECT_EQ(log_grid(1e5, 1.0001e5, 1).size(), 2u);  // narrower than a point's share: the two ends
  EXPECT_THROW(log_grid(0.0, 1.0, 1), std::invalid_argument);
}

// A range wider than the doubles' own (hi / lo = 1e310 overflows) is still 310 decades: the grid
// was {NaN, hi}, and contact_cost --k-min 1e-300 ran a spring of k = NaN.
TEST(LogGrid, ARangeWhoseRatioOverflowsIsStillADecadeGrid) {
  const auto wide = log_grid(1e-300, 1e10, 1);
  ASSERT_EQ(wide.size(), 311u);
  // 1e-12: some 20 ulps of the logs' magnitude (up to 300, an ulp 5.7e-14), for the rounding of
  // decades j / n, of pow and of log10.
  for (std::size_t j = 0; j < wide.size(); ++j)
    EXPECT_NEAR(std::log10(wide[j]), -300 + static_cast<double>(j), 1e-12) << j;
  EXPECT_EQ(wide.front(), 1e-300);
  EXPECT_EQ(wide.back(), 1e10);
}

// y = C x^p exactly: the fit returns p and C to rounding, with r^2 = 1.
TEST(PowerFit, AnExactPowerLawIsFittedExactly) {
  const std::vector<double> x{1e-3, 1e-2, 1e-1, 1.0};
  std::vector<double> y;
  for (double v : x) y.push_back(2.5 * std::pow(v, 1.5));
  const PowerFit f = fit_power_law(x, y);
  EXPECT_NEAR(f.exponent, 1.5, 1e-12);
  EXPECT_NEAR(f.coefficient, 2.5, 1e-11);
  EXPECT_NEAR(f.r_squared, 1.0, 1e-12);
  EXPECT_NEAR(observed_order(1e-2, y[1], 1e-3, y[0]), 1.5, 1e-12);
}

// Two points determine the line and leave no residual to estimate its error from (GSL divides by
// n - 2): the standard error is NaN, a dash in the tables, where it came out infinite or NaN by
// the rounding of a residual that is zero. Three points give the usual error.
TEST(PowerFit, TwoPointsGiveTheExponentButNoStandardError) {
  for (const std::vector<double>& y :
       {std::vector<double>{1.0, 7.0}, std::vector<double>{3e-4, 2.9991e-4}, std::vector<double>{0.3, 0.1}}) {
    const std::vector<double> x{1e5, 1.0001e5};
    const PowerFit f = fit_power_law(x, y);
    EXPECT_NEAR(f.exponent, observed_order(x[0], y[0], x[1], y[1]), 1e-9 * std::abs(f.exponent));
    EXPECT_TRUE(std::isnan(f.exponent_sd)) << f.exponent_sd;
    const LineFit l = fit_line(x, y);
    EXPECT_NEAR(l.slope, (y[1] - y[0]) / (x[1] - x[0]), 1e-9 * std::abs(l.slope));
    EXPECT_TRUE(std::isnan(l.slope_sd)) << l.slope_sd;
  }
  const PowerFit three = fit_power_law({1.0, 2.0, 4.0}, {1.0, 4.1, 15.9});
  EXPECT_GT(three.exponent_sd, 0);
  EXPECT_LT(three.exponent_sd, 0.05);
}
