#pragma once
// Least-squares fits in log-log space (GSL): y ~ C x^p gives the observed order or exponent p.
#include <cstddef>
#include <limits>
#include <vector>

namespace contact {

struct PowerFit {
  double exponent;     // p
  double coefficient;  // C
  double exponent_sd;  // standard error of p from the fit's covariance; NaN from two points
  double r_squared;
};

// Requires at least two points with x > 0 and y > 0; throws std::invalid_argument otherwise.
PowerFit fit_power_law(const std::vector<double>& x, const std::vector<double>& y);

// Observed order between two rows of a convergence table, (h_prev, err_prev) and (h, err):
// log(err_prev / err) / log(h_prev / h), where h is a step, a tolerance or 1/k.
double observed_order(double h_prev, double err_prev, double h, double err);

// The order fitted (fit_power_law) over the last `rows` points with floor < err < ceiling: the
// finest rows of a table ordered coarse to fine, above rounding and, below the ceiling, small
// enough for the error's leading term to dominate (the asymptotic range). NaN when fewer than two
// remain.
double fitted_order(const std::vector<double>& h, const std::vector<double>& err, double floor,
                    std::size_t rows, double ceiling = std::numeric_limits<double>::infinity());

// One row of a convergence study, coarse to fine: the step (dt, rtol or 1/k), the error, the cost.
struct ConvergencePoint {
  double step;
  double error;
  long cost = 0;
};
// fitted_order over the points' steps and errors.
double fitted_order(const std::vector<ConvergencePoint>& points, double floor, std::size_t rows,
                    double ceiling = std::numeric_limits<double>::infinity());

// Points from lo to hi (0 < lo <= hi), evenly spaced in log, per_decade >= 1 of them per decade
// (rounded; at least the two ends), the ends exact: lo * (hi/lo)^(j/n), a whole number of decades
// above lo exactly lo * 10^m. lo == hi gives one point.
std::vector<double> log_grid(double lo, double hi, long per_decade);

// Ordinary least squares y ~ intercept + slope x (GSL), e.g. an energy drift rate.
struct LineFit {
  double slope;
  double intercept;
  double slope_sd;  // standard error of the slope from the fit's covariance; NaN from two points
};
// Requires at least two pairs of finite values; throws std::invalid_argument otherwise.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace contact

namespace contact {
// GSL's version, e.g. "2.7.1", for run metadata.
const char* gsl_version_string();
}  // namespace contact
