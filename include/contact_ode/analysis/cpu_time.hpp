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
};
// Runs f `repeats` (>= 1) times and times each call.
CpuTiming time_cpu(const std::function<void()>& f, int repeats);

}  // namespace contact
