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

CpuTiming time_cpu(const std::function<void()>& f, int repeats) {
  if (repeats < 1) throw std::invalid_argument("time_cpu: repeats must be >= 1");
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const double start = cpu_seconds();
    f();
    t.push_back(cpu_seconds() - start);
  }
  std::sort(t.begin(), t.end());
  const std::size_t n = t.size();
  const double median = n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
  return {median, t.front(), t.back(), repeats};
}

}  // namespace contact
