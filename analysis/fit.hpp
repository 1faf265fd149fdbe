#pragma once
// Least-squares fits in log-log space (GSL): y ~ C x^p gives the observed order or exponent p.
#include <vector>

namespace contact {

struct PowerFit {
  double exponent;      // p
  double coefficient;   // C
  double exponent_sd;   // standard error of p from the fit's covariance
  double r_squared;
};

// Requires at least two points with x > 0 and y > 0; throws std::invalid_argument otherwise.
PowerFit fit_power_law(const std::vector<double>& x, const std::vector<double>& y);

// Ordinary least squares y ~ intercept + slope x (GSL), e.g. an energy drift rate.
struct LineFit {
  double slope;
  double intercept;
  double slope_sd;  // standard error of the slope from the fit's covariance
};
// Requires at least two pairs of finite values; throws std::invalid_argument otherwise.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace contact

namespace contact {
// GSL's version, e.g. "2.7.1", for run metadata.
const char* gsl_version_string();
}  // namespace contact
