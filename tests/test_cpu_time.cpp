// The study's CPU timings (analysis/cpu_time.hpp): what a timing counts and what it leaves out.
// Calls burn the process's CPU clock for set times, so each count is known to within the
// overhead of a few clock reads (microseconds; the tolerances, 5 ms, are half the shortest burn).
#include "contact_ode/analysis/cpu_time.hpp"

#include <gtest/gtest.h>

using namespace contact;

namespace {

// Runs until the CPU clock has advanced by s; returns the CPU time it took (>= s).
double burn(double s) {
  const double start = cpu_seconds();
  volatile double sink = 0;
  while (cpu_seconds() - start < s) sink = sink + 1;
  return cpu_seconds() - start;
}

}  // namespace

// An engine's world construction is paid once per world: a rate per simulated second leaves it
// out, and the timing reports it apart. A call that spends 20 ms it says to leave out and 10 ms
// it does not is timed at the 10 ms alone.
TEST(CpuTime, WhatACallSaysToLeaveOutIsNotCountedButReported) {
  const CpuTiming t = time_cpu_excluding(
      [] {
        const double setup = burn(0.02);
        burn(0.01);
        return setup;
      },
      3, 3, 0.0);
  EXPECT_EQ(t.repeats, 3);
  EXPECT_GE(t.min, 0.01);
  EXPECT_LT(t.max, 0.015);
  EXPECT_GE(t.left_out, 0.02);
  EXPECT_LT(t.left_out, 0.025);
  const CpuTiming whole = time_cpu([] { burn(0.01); }, 3);  // the plain timing counts it all
  EXPECT_GE(whole.min, 0.01);
  EXPECT_EQ(whole.left_out, 0.0);
}
