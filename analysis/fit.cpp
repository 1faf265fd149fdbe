#include "contact_ode/analysis/fit.hpp"

#include "contact_ode/integrators/gsl_handles.hpp"

#include <gsl/gsl_fit.h>
#include <gsl/gsl_statistics_double.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace contact {

namespace {
// The standard error from GSL's covariance, which scales the residual by 1 / (n - 2): two points
// leave no residual to estimate it from, and GSL's 0 / 0 or rounding / 0 gave NaN or infinity
// (both in one table): undefined, NaN.
double standard_error(double variance, std::size_t points) {
  return points > 2 ? std::sqrt(variance) : std::numeric_limits<double>::quiet_NaN();
}
}  // namespace

PowerFit fit_power_law(const std::vector<double>& x, const std::vector<double>& y) {
  gsl::report_errors_by_return_code();
  if (x.size() != y.size() || x.size() < 2)
    throw std::invalid_argument("fit_power_law: need two or more (x, y) pairs");
  std::vector<double> lx, ly;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0) || !(y[i] > 0)) throw std::invalid_argument("fit_power_law: x and y must be positive");
    lx.push_back(std::log(x[i]));
    ly.push_back(std::log(y[i]));
  }
  double c0, c1, cov00, cov01, cov11, sumsq;
  gsl_fit_linear(lx.data(), 1, ly.data(), 1, lx.size(), &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
  const double tss = gsl_stats_tss(ly.data(), 1, ly.size());
  return {c1, std::exp(c0), standard_error(cov11, lx.size()), tss > 0 ? 1.0 - sumsq / tss : 1.0};
}

double observed_order(double h_prev, double err_prev, double h, double err) {
  return std::log(err_prev / err) / std::log(h_prev / h);
}

double fitted_order(const std::vector<double>& h, const std::vector<double>& err, double floor,
                    std::size_t rows, double ceiling) {
  std::vector<double> x, y;
  for (std::size_t i = 0; i < h.size() && i < err.size(); ++i)
    if (err[i] > floor && err[i] < ceiling) {
      x.push_back(h[i]);
      y.push_back(err[i]);
    }
  if (x.size() > rows) {
    x.erase(x.begin(), x.end() - static_cast<std::ptrdiff_t>(rows));
    y.erase(y.begin(), y.end() - static_cast<std::ptrdiff_t>(rows));
  }
  return x.size() >= 2 ? fit_power_law(x, y).exponent : std::nan("");
}

double fitted_order(const std::vector<ConvergencePoint>& points, double floor, std::size_t rows,
                    double ceiling) {
  std::vector<double> h, err;
  for (const auto& p : points) {
    h.push_back(p.step);
    err.push_back(p.error);
  }
  return fitted_order(h, err, floor, rows, ceiling);
}

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  gsl::report_errors_by_return_code();
  if (x.size() != y.size() || x.size() < 2)
    throw std::invalid_argument("fit_line: need two or more (x, y) pairs");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]))
      throw std::invalid_argument("fit_line: x and y must be finite");
  double c0, c1, cov00, cov01, cov11, sumsq;
  gsl_fit_linear(x.data(), 1, y.data(), 1, x.size(), &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
  return {c1, c0, standard_error(cov11, x.size())};
}

}  // namespace contact

#include <gsl/gsl_version.h>

namespace contact {
const char* gsl_version_string() { return gsl_version; }
std::vector<double> log_grid(double lo, double hi, long per_decade) {
  if (!(lo > 0 && hi >= lo && std::isfinite(hi) && per_decade >= 1))
    throw std::invalid_argument("log_grid: needs 0 < lo <= hi < inf and per_decade >= 1");
  if (hi == lo) return {lo};
  // The decades as a difference of logs: hi / lo overflows (1e10 / 1e-300), and its log of inf
  // made the grid {NaN, hi}.
  const double decades = std::log10(hi) - std::log10(lo);
  // At least one interval: a range narrower than a point's share of a decade (1e5 ... 1.0001e5)
  // used to round to zero intervals and divide by zero (k = NaN).
  const long n = std::max(1L, std::lround(decades * static_cast<double>(per_decade)));
  // A whole number of decades above lo is lo times an exact power of ten: (hi/lo)^(j/n) put the
  // sweeps' k = 1e3 at 999.99999999999977 in their CSV files, which a reader's k == 1000 missed.
  std::vector<double> grid;
  for (long j = 0; j < n; ++j) {
    const double d = decades * static_cast<double>(j) / static_cast<double>(n);
    const double whole = std::round(d);
    // 1e-9 of a decade: the log's rounding is ~1e-15, the grid's spacing at least 1e-2 (the programs' cap of
    // 100 a decade).
    const double exponent = std::abs(d - whole) < 1e-9 ? whole : d;
    const double scale = std::pow(10.0, exponent);  // inf past 308 decades above lo (lo < 1)
    grid.push_back(std::isfinite(scale) ? lo * scale : std::pow(10.0, std::log10(lo) + exponent));
  }
  grid.push_back(hi);
  return grid;
}

}  // namespace contact
