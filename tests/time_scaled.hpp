#pragma once
// A ball drop run in other time units (the step, the span and 1 / sqrt(g) and 1 / sqrt(k / m)
// times s) is the same motion, its velocities 1 / s times: the tests of methods that must not
// depend on the units of time run it through this one check.
#include "contact_ode/integrators/run_result.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <initializer_list>

// run(s) for each s against run(1): every sample's height and velocity (scaled back by s) within
// `tol`, and `also` (if given) applied to each scaled run.
inline void expect_the_same_motion_in_other_time_units(
    const std::function<contact::RunResult(double s)>& run, std::initializer_list<double> scales, double tol,
    const std::function<void(const contact::RunResult&, double s)>& also = {}) {
  const contact::RunResult one = run(1.0);
  ASSERT_TRUE(one.ok()) << one.message;
  for (const double s : scales) {
    const contact::RunResult r = run(s);
    ASSERT_TRUE(r.ok()) << s << ": " << r.message;
    ASSERT_EQ(r.samples.size(), one.samples.size()) << s;
    for (std::size_t n = 0; n < one.samples.size(); ++n) {
      EXPECT_NEAR(r.samples[n].y[0], one.samples[n].y[0], tol) << s << " sample " << n;
      EXPECT_NEAR(r.samples[n].y[1] * s, one.samples[n].y[1], tol) << s << " sample " << n;
    }
    if (also) also(r, s);
  }
}
