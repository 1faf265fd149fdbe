#pragma once
// CPU time, as the study reports it: the process's CPU clock (not wall time, which another
// process on the machine would inflate), as the median of repeats with its spread.
#include <functional>

namespace contact {

// CPU time this process has used [s] (CLOCK_PROCESS_CPUTIME_ID).
double cpu_seconds();

struct CpuTiming {
  double median;  // [s]
  double min, max;
  int repeats;
  double left_out = 0;  // time_cpu_excluding: the median of what the calls left out [s]
};
// Runs f `repeats` (>= 1) times and times each call.
CpuTiming time_cpu(const std::function<void()>& f, int repeats);
// Runs f at least `min_repeats` (>= 1) and at most `max_repeats` times, stopping once the calls
// have used `budget_s` of CPU time: ten repeats of a solve of a millisecond, three of a slow one
// (whose timer noise is relatively small), so that a sweep's timing costs a bounded multiple.
CpuTiming time_cpu_within(const std::function<void()>& f, int min_repeats, int max_repeats, double budget_s);
// time_cpu_within for a call f that returns the CPU seconds of itself to leave out: each call's
// time is what remains (an engine's world construction, paid once per world, left out of a rate
// per simulated second); the budget counts whole calls.
CpuTiming time_cpu_excluding(const std::function<double()>& f, int min_repeats, int max_repeats,
                             double budget_s);

}  // namespace contact
