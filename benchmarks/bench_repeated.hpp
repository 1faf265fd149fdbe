#pragma once
// One way of timing a case for bench_report: one iteration a repetition, five repetitions,
// reported as median, min and max of CPU time (the spread the report shows), in milliseconds.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

namespace contact::bench {

inline double smallest(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }
inline double largest(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

// N = 10, 100, ... up to `most`, each repeated as above.
inline void repeated_sizes(benchmark::internal::Benchmark* b, long most) {
  b->RangeMultiplier(10)
      ->Range(10, most)
      ->Iterations(1)
      ->Repetitions(5)
      ->ReportAggregatesOnly(true)
      ->ComputeStatistics("min", smallest)
      ->ComputeStatistics("max", largest)
      ->Unit(benchmark::kMillisecond);
}

}  // namespace contact::bench
