#include "contact_ode/analysis/cpu_time.hpp"

#include <algorithm>
#include <ctime>
#include <stdexcept>
#include <vector>

namespace contact {

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

namespace {

double median_of(std::vector<double>& t) {  // t not empty; sorts it
  std::sort(t.begin(), t.end());
  const std::size_t n = t.size();
  return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

}  // namespace

CpuTiming time_cpu_excluding(const std::function<double()>& f, int min_repeats, int max_repeats,
                             double budget_s) {
  if (min_repeats < 1 || max_repeats < min_repeats)
    throw std::invalid_argument("time_cpu: repeats must satisfy 1 <= min_repeats <= max_repeats");
  std::vector<double> t, left_out;
  double used = 0;
  while (static_cast<int>(t.size()) < min_repeats ||
         (static_cast<int>(t.size()) < max_repeats && used < budget_s)) {
    const double start = cpu_seconds();
    const double out = f();
    const double whole = cpu_seconds() - start;
    t.push_back(whole - out);
    left_out.push_back(out);
    used += whole;
  }
  const double median = median_of(t);
  return {median, t.front(), t.back(), static_cast<int>(t.size()), median_of(left_out)};
}

CpuTiming time_cpu(const std::function<void()>& f, int repeats) {
  return time_cpu_within(f, repeats, repeats, 0.0);
}

CpuTiming time_cpu_within(const std::function<void()>& f, int min_repeats, int max_repeats, double budget_s) {
  return time_cpu_excluding(
      [&] {
        f();
        return 0.0;
      },
      min_repeats, max_repeats, budget_s);
}

}  // namespace contact
