// The progress line a sweep shows on a terminal: one row whatever the window's width.
#include "progress.hpp"

#include <gtest/gtest.h>

namespace {

using contact::progress_line;

TEST(ProgressLine, FitsTheWindowLeavingItsLastColumnFree) {
  EXPECT_EQ(progress_line("k_sweep", 3, 75, "hooke k = 464", 0), "k_sweep [3/75] hooke k = 464");
  EXPECT_EQ(progress_line("k_sweep", 3, 75, "hooke k = 464", 80), "k_sweep [3/75] hooke k = 464");
  // A line as wide as the window wraps at its last character on some terminals: one column spare.
  EXPECT_EQ(progress_line("k_sweep", 3, 75, "hooke k = 464", 28), "k_sweep [3/75] hooke k = 46");
  EXPECT_EQ(progress_line("k_sweep", 3, 75, "hooke k = 464", 29), "k_sweep [3/75] hooke k = 464");
  EXPECT_EQ(progress_line("k_sweep", 3, 75, "hooke k = 464", 10), "k_sweep [");
  EXPECT_EQ(progress_line("k_sweep", 3, 75, "hooke k = 464", 1), "");
}

}  // namespace
